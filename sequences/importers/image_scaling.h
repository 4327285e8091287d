// Down-scaling a data set's images to robot-camera size, with the camera matrix scaled to match.
#pragma once

#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "util/status.h"

namespace sfm {

struct ImageScaleOptions {
  double scale = 0;      // factor for both image axes, in (0, 1]; 0: use max_width instead
  int max_width = 768;   // pixels: wider images are scaled down to this width (when scale is 0); 0: keep the size

  Status Check() const;
};

// Size of a width x height image after scaling: each side rounded to the nearest pixel, at least 1.
cv::Size ScaledImageSize(int width, int height, const ImageScaleOptions& options);

// The camera of an image resized from camera.width x camera.height to `size` by cv::resize. With
// OpenCV's pixel-centre convention resize maps x to x' = s (x + 0.5) - 0.5, s = size.width / width
// (and likewise in y), so fx' = s fx and cx' = s (cx + 0.5) - 0.5. Distortion coefficients act on
// normalised coordinates and stay as they are.
Camera ScaleCamera(const Camera& camera, const cv::Size& size);

}  // namespace sfm

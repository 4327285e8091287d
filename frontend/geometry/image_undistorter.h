// ImageUndistorter: resamples images of a distorted camera to its undistorted geometry (same size
// and K). The remap tables are built once per camera, not once per frame.
#pragma once

#include <opencv2/core.hpp>

#include "frontend/geometry/camera.h"

namespace sfm {

class ImageUndistorter {
 public:
  explicit ImageUndistorter(const Camera& camera);

  // The undistorted image (bilinear resampling, black outside the field of view); a shallow copy
  // of the input when the camera has no distortion. CHECKs that the image is of the camera's size.
  cv::Mat Apply(const cv::Mat& image) const;

 private:
  int width_, height_;
  cv::Mat map_x_, map_y_;  // empty when there is no distortion
};

}  // namespace sfm

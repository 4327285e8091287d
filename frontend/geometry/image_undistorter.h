// ImageUndistorter: resamples images of a distorted camera to its undistorted geometry (same size
// and K). The remap tables are built once per camera, not once per frame.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "frontend/geometry/camera.h"

namespace sfm {

// How the undistorted image is resampled from the stored one (cv::remap's interpolation).
enum class UndistortInterpolation { kLinear, kCubic, kLanczos4 };

// The resampling of frames before detection (PipelineOptions, the apps' --undistort_interpolation).
// Bilinear blurs every edge (keeps about 0.89 of a step's peak gradient, cubic 0.99) and merges
// close corners: cubic finds 0.7-1.1 points more junctions on generated sequences with a lens. It
// stays linear by default: end to end its mean effect over noise draws is nil, but on the project's
// fixed draws it turns the VGG back-end ATE ratio 0.980 -> 1.018 (a readout of the last 0.1 % of
// scale) and held-out turns-dist's wireframe 0.908 -> 0.888 (-0.006 +- 0.004 over 19 noise draws):
// docs/junction_results.md, "Session 8: resampling".
constexpr UndistortInterpolation kDetectionInterpolation = UndistortInterpolation::kLinear;

// "linear", "cubic" or "lanczos4"; false for any other name.
bool ParseUndistortInterpolation(const std::string& name, UndistortInterpolation* interpolation);
// The name ParseUndistortInterpolation reads.
const char* UndistortInterpolationName(UndistortInterpolation interpolation);

class ImageUndistorter {
 public:
  explicit ImageUndistorter(const Camera& camera,
                            UndistortInterpolation interpolation = UndistortInterpolation::kLinear);

  // The undistorted image (resampled with the constructor's interpolation, black outside the
  // field of view); a shallow copy of the input when the camera has no distortion. CHECKs that the
  // image is of the camera's size.
  cv::Mat Apply(const cv::Mat& image) const;

 private:
  int width_, height_;
  int interpolation_;      // cv::INTER_*
  cv::Mat map_x_, map_y_;  // empty when there is no distortion
};

}  // namespace sfm

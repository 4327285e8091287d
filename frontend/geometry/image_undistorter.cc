#include "frontend/geometry/image_undistorter.h"

#include <glog/logging.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace sfm {

bool ParseUndistortInterpolation(const std::string& name, UndistortInterpolation* interpolation) {
  if (name == "linear")
    *interpolation = UndistortInterpolation::kLinear;
  else if (name == "cubic")
    *interpolation = UndistortInterpolation::kCubic;
  else if (name == "lanczos4")
    *interpolation = UndistortInterpolation::kLanczos4;
  else
    return false;
  return true;
}

const char* UndistortInterpolationName(UndistortInterpolation interpolation) {
  switch (interpolation) {
    case UndistortInterpolation::kCubic:
      return "cubic";
    case UndistortInterpolation::kLanczos4:
      return "lanczos4";
    default:
      return "linear";
  }
}

ImageUndistorter::ImageUndistorter(const Camera& camera, UndistortInterpolation interpolation)
    : width_(camera.width),
      height_(camera.height),
      interpolation_(interpolation == UndistortInterpolation::kCubic      ? cv::INTER_CUBIC
                     : interpolation == UndistortInterpolation::kLanczos4 ? cv::INTER_LANCZOS4
                                                                          : cv::INTER_LINEAR) {
  if (!camera.HasDistortion()) return;
  const cv::Matx33d camera_matrix(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Matx<double, 1, 5> coefficients(camera.distortion[0], camera.distortion[1], camera.distortion[2],
                                            camera.distortion[3], camera.distortion[4]);
  // Float maps: the fixed-point CV_16SC2 maps quantise to 1/32 px.
  cv::initUndistortRectifyMap(camera_matrix, coefficients, cv::noArray(), camera_matrix,
                              cv::Size(camera.width, camera.height), CV_32FC1, map_x_, map_y_);
}

cv::Mat ImageUndistorter::Apply(const cv::Mat& image) const {
  CHECK_EQ(image.cols, width_);
  CHECK_EQ(image.rows, height_);
  if (map_x_.empty()) return image;
  cv::Mat undistorted;
  cv::remap(image, undistorted, map_x_, map_y_, interpolation_, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  return undistorted;
}

}  // namespace sfm

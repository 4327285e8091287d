#include "geometry/camera.h"

#include <glog/logging.h>

#include <Eigen/LU>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <vector>

#include "geometry/image_undistorter.h"

namespace sfm {
namespace {

// Newton stops when a step moves the normalised point by less than this; 1e-12 in normalised
// units is ~1e-9 px for any realistic focal length.
constexpr double kUndistortStepTolerance = 1e-12;
constexpr int kUndistortMaxIterations = 50;

// cv::fisheye::undistortPoints' Newton iteration on theta: 1e-14 rad is ~1e-11 px for any focal length.
const cv::TermCriteria kFisheyeUndistortCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                                 kUndistortMaxIterations, 1e-14);

}  // namespace

bool ParseDistortionModel(const std::string& name, DistortionModel* model) {
  if (name == "radtan")
    *model = DistortionModel::kRadTan;
  else if (name == "equidistant")
    *model = DistortionModel::kEquidistant;
  else
    return false;
  return true;
}

const char* DistortionModelName(DistortionModel model) {
  return model == DistortionModel::kEquidistant ? "equidistant" : "radtan";
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d K;
  K << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return K;
}

bool Camera::HasDistortion() const {
  if (model == DistortionModel::kEquidistant) return true;
  for (double d : distortion) {
    if (d != 0) return true;
  }
  return false;
}

cv::Mat Camera::DistortionCoefficients() const {
  const int count = model == DistortionModel::kEquidistant ? 4 : 5;
  cv::Mat coefficients(1, count, CV_64F);
  for (int i = 0; i < count; ++i) coefficients.at<double>(i) = distortion[i];
  return coefficients;
}

Eigen::Vector2d Camera::Distort(const Eigen::Vector2d& normalised) const {
  if (model == DistortionModel::kEquidistant) {
    const std::vector<cv::Point2d> in{{normalised.x(), normalised.y()}};
    std::vector<cv::Point2d> out;
    cv::fisheye::distortPoints(in, out, cv::Matx33d::eye(), DistortionCoefficients());
    return {out[0].x, out[0].y};
  }
  const auto& [k1, k2, p1, p2, k3] = distortion;
  const double x = normalised.x(), y = normalised.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
          y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

Eigen::Vector2d Camera::Undistort(const Eigen::Vector2d& distorted) const {
  if (!HasDistortion()) return distorted;
  if (model == DistortionModel::kEquidistant) {
    const std::vector<cv::Point2d> in{{distorted.x(), distorted.y()}};
    std::vector<cv::Point2d> out;
    cv::fisheye::undistortPoints(in, out, cv::Matx33d::eye(), DistortionCoefficients(), cv::noArray(),
                                 cv::noArray(), kFisheyeUndistortCriteria);
    return {out[0].x, out[0].y};
  }
  const auto& [k1, k2, p1, p2, k3] = distortion;
  // The distorted point is the natural start: the model is a perturbation of the identity.
  Eigen::Vector2d u = distorted;
  for (int iteration = 0; iteration < kUndistortMaxIterations; ++iteration) {
    const double x = u.x(), y = u.y();
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double radial_derivative = k1 + r2 * (2 * k2 + 3 * k3 * r2);  // d radial / d r2
    Eigen::Matrix2d J;
    J(0, 0) = radial + 2 * x * x * radial_derivative + 2 * p1 * y + 6 * p2 * x;
    J(0, 1) = 2 * x * y * radial_derivative + 2 * p1 * x + 2 * p2 * y;
    J(1, 0) = J(0, 1);
    J(1, 1) = radial + 2 * y * y * radial_derivative + 6 * p1 * y + 2 * p2 * x;
    const Eigen::Vector2d step = J.partialPivLu().solve(Distort(u) - distorted);
    if (!step.allFinite()) break;
    u -= step;
    if (step.norm() < kUndistortStepTolerance) break;
  }
  return u;
}

Eigen::Vector2d Camera::Project(const Eigen::Vector3d& point_camera) const {
  CHECK_GT(point_camera.z(), 0) << "Project: point behind the camera";
  const Eigen::Vector2d d = Distort(point_camera.head<2>() / point_camera.z());
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector2d Camera::ProjectUndistorted(const Eigen::Vector3d& point_camera) const {
  CHECK_GT(point_camera.z(), 0) << "ProjectUndistorted: point behind the camera";
  return {fx * point_camera.x() / point_camera.z() + cx, fy * point_camera.y() / point_camera.z() + cy};
}

Eigen::Vector2d Camera::UndistortPixel(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d u = Undistort({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
  return {fx * u.x() + cx, fy * u.y() + cy};
}

Eigen::Vector2d Camera::DistortPixel(const Eigen::Vector2d& undistorted_pixel) const {
  const Eigen::Vector2d d = Distort({(undistorted_pixel.x() - cx) / fx, (undistorted_pixel.y() - cy) / fy});
  return {fx * d.x() + cx, fy * d.y() + cy};
}

cv::Mat Camera::UndistortImage(const cv::Mat& image) const {
  return ImageUndistorter(*this).Apply(image).clone();
}

}  // namespace sfm

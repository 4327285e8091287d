#include "sequences/generator/camera_rig.h"

#include <cmath>
#include <string>

namespace sfm {

Status CameraRigOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("camera options: " + what); };
  if (width < 16 || height < 16 || width > 8192 || height > 8192) return error("width and height must be in [16, 8192] px");
  if (!(fx > 0 && fy > 0 && fx < 1e5 && fy < 1e5)) return error("fx and fy must be in (0, 1e5) px");
  if (!std::isfinite(cx) || !std::isfinite(cy) || cx >= width || cy >= height) {
    return error("cx and cy must be inside the image (or negative for its centre)");
  }
  for (double d : distortion) {
    if (!(std::abs(d) < 10)) return error("distortion coefficients must be finite and below 10 in magnitude");
  }
  if (model == DistortionModel::kEquidistant && distortion[4] != 0) {
    return error("the equidistant lens has four coefficients k1 k2 k3 k4 (the fifth must be 0)");
  }
  if (!(mount_height > 0.1 && mount_height < 3)) return error("mount_height must be in (0.1, 3) m");
  if (!(std::abs(mount_forward) < 1)) return error("mount_forward must be in (-1, 1) m");
  if (!(std::abs(pitch) < 1.2)) return error("pitch must be in (-1.2, 1.2) rad");
  return Status::Ok();
}

Camera CameraRigOptions::MakeCamera() const {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = fx;
  camera.fy = fy;
  camera.cx = cx < 0 ? 0.5 * (width - 1) : cx;
  camera.cy = cy < 0 ? 0.5 * (height - 1) : cy;
  camera.model = model;
  camera.distortion = distortion;
  return camera;
}

double CameraRigOptions::EquidistantFocalForDiagonal(double diagonal_rad) const {
  // cv::fisheye: the corner's distorted radius is f theta_d(theta), theta = half the diagonal.
  const double theta = 0.5 * diagonal_rad, t2 = theta * theta;
  const double theta_d =
      theta * (1 + t2 * (distortion[0] + t2 * (distortion[1] + t2 * (distortion[2] + t2 * distortion[3]))));
  return 0.5 * std::hypot(width, height) / theta_d;
}

Pose3 CameraRigOptions::BaseTCamera() const {
  // Columns: the camera axes in the base frame.
  const double c = std::cos(pitch), s = std::sin(pitch);
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, -1, 0);  // camera x: right = -base y
  R.col(1) = Eigen::Vector3d(-s, 0, -c);  // camera y: down, tilted back by the pitch
  R.col(2) = Eigen::Vector3d(c, 0, -s);  // camera z: forward, tilted down by the pitch
  return Pose3(R, Eigen::Vector3d(mount_forward, 0, mount_height));
}

}  // namespace sfm

#include "tests/triangulation/synthetic_cameras.h"

#include <Eigen/Geometry>
#include <cmath>

namespace sfm::testing {

Eigen::Matrix3d TestK() {
  Eigen::Matrix3d K;
  K << 450, 0, 319.5, 0, 450, 239.5, 0, 0, 1;
  return K;
}

Pose3 LookAt(const Eigen::Vector3d& centre, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - centre).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_R_camera;
  world_R_camera << x, y, z;
  return Pose3(world_R_camera, centre);
}

std::vector<Pose3> ForwardCameras() {
  std::vector<Pose3> cameras;
  for (int k = 0; k < 5; ++k)
    cameras.push_back(LookAt(Eigen::Vector3d(0.4 * k, 0, 1), Eigen::Vector3d(10, 0, 1)));
  return cameras;
}

Eigen::Vector2d Project(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector3d& point) {
  return (K * (world_T_camera.Inverse() * point)).hnormalized();
}

Eigen::Vector2d PixelNoise(std::mt19937& random, double sigma_px) {
  std::normal_distribution<double> normal(0.0, sigma_px);
  const double x = normal(random);
  return Eigen::Vector2d(x, normal(random));
}

double LineAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

double DistanceToLine(const Eigen::Vector3d& x, const Eigen::Vector3d& point,
                      const Eigen::Vector3d& direction) {
  return (x - point).cross(direction).norm();
}

}  // namespace sfm::testing

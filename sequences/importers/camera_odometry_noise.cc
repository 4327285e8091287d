#include "sequences/importers/camera_odometry_noise.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "sequences/generator/random.h"

namespace sfm {
namespace {

// Exp of a rotation vector; exactly the identity for the zero vector (noise-free odometry then
// reproduces the truth to rounding).
Eigen::Quaterniond RotationFromVector(const Eigen::Vector3d& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation_vector / angle));
}

}  // namespace

Status CameraOdometryNoiseOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("odometry noise options: " + what); };
  if (!(scale_error > -0.5 && scale_error < 0.5)) return error("scale_error must be in (-0.5, 0.5)");
  if (!(distance_sigma >= 0 && distance_sigma < 0.5)) return error("distance_sigma must be in [0, 0.5)");
  if (!(rotation_sigma >= 0 && rotation_sigma < 0.5)) return error("rotation_sigma must be in [0, 0.5) rad");
  if (!(std::abs(rotation_bias) < 0.5)) return error("rotation_bias must be in (-0.5, 0.5) rad");
  return Status::Ok();
}

CameraOdometryNoiseOptions CameraOdometryNoiseOptions::Scaled(double factor) const {
  CameraOdometryNoiseOptions scaled = *this;
  scaled.scale_error *= factor;
  scaled.distance_sigma *= factor;
  scaled.rotation_sigma *= factor;
  scaled.rotation_bias *= factor;
  return scaled;
}

OdometryNoise CameraOdometryNoiseOptions::ForCalibration() const {
  OdometryNoise noise;
  noise.translation_sigma = std::max(1e-4, std::hypot(scale_error, distance_sigma));
  noise.rotation_sigma = std::max(1e-5, std::hypot(rotation_sigma, rotation_bias));
  return noise;
}

std::vector<Pose3> SimulateCameraOdometry(const std::vector<Pose3>& world_T_camera_true,
                                          const CameraOdometryNoiseOptions& options, std::uint64_t seed) {
  std::vector<Pose3> odometry;
  if (world_T_camera_true.empty()) return odometry;
  Random random(seed);
  odometry.push_back(world_T_camera_true.front());
  for (size_t i = 1; i < world_T_camera_true.size(); ++i) {
    const Pose3 motion = world_T_camera_true[i - 1].Inverse() * world_T_camera_true[i];
    const double n1 = random.Gaussian();
    const double n2 = random.Gaussian(), n3 = random.Gaussian(), n4 = random.Gaussian();
    const double scale = (1 + options.scale_error) * (1 + options.distance_sigma * n1);
    const Eigen::Vector3d rotation_error =
        options.rotation_bias * Eigen::Vector3d::UnitY() + options.rotation_sigma * Eigen::Vector3d(n2, n3, n4);
    const Pose3 noisy((RotationFromVector(rotation_error) * motion.rotation).normalized(), scale * motion.translation);
    odometry.push_back(odometry.back() * noisy);
  }
  return odometry;
}

}  // namespace sfm

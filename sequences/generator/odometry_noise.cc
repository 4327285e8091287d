#include "sequences/generator/odometry_noise.h"

#include <algorithm>
#include <cmath>

#include "sequences/generator/random.h"

namespace sfm {

Status OdometryNoiseOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("odometry noise options: " + what); };
  if (!(scale_error > -0.5 && scale_error < 0.5)) return error("scale_error must be in (-0.5, 0.5)");
  if (!(distance_sigma >= 0 && distance_sigma < 0.5)) return error("distance_sigma must be in [0, 0.5)");
  if (!(heading_sigma >= 0 && heading_sigma < 0.5)) return error("heading_sigma must be in [0, 0.5) rad");
  if (!(std::abs(heading_bias) < 0.5)) return error("heading_bias must be in (-0.5, 0.5) rad");
  return Status::Ok();
}

OdometryNoiseOptions OdometryNoiseOptions::Scaled(double factor) const {
  OdometryNoiseOptions scaled = *this;
  scaled.scale_error *= factor;
  scaled.distance_sigma *= factor;
  scaled.heading_sigma *= factor;
  scaled.heading_bias *= factor;
  return scaled;
}

OdometryNoise OdometryNoiseOptions::ForCalibration() const {
  OdometryNoise noise;
  noise.translation_sigma = std::max(1e-4, std::hypot(scale_error, distance_sigma));
  noise.rotation_sigma = std::max(1e-5, std::hypot(heading_sigma, heading_bias));
  return noise;
}

std::vector<Pose3> SimulateOdometry(const std::vector<Pose3>& world_T_base_true, const OdometryNoiseOptions& options,
                                    std::uint64_t seed) {
  std::vector<Pose3> odometry;
  if (world_T_base_true.empty()) return odometry;
  Random random(seed);
  odometry.push_back(world_T_base_true.front());
  for (size_t i = 1; i < world_T_base_true.size(); ++i) {
    const Pose3 motion = world_T_base_true[i - 1].Inverse() * world_T_base_true[i];
    const double n1 = random.Gaussian(), n2 = random.Gaussian();
    const double scale = (1 + options.scale_error) * (1 + options.distance_sigma * n1);
    const double heading = options.heading_bias + options.heading_sigma * n2;
    const Pose3 noisy(
        (Eigen::Quaterniond(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ())) * motion.rotation).normalized(),
        scale * motion.translation);
    odometry.push_back(odometry.back() * noisy);
  }
  return odometry;
}

}  // namespace sfm

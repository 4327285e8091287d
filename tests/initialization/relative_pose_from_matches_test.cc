// The relative pose the images give a pair (RelativePoseFromMatches, the source of the pose graph's
// constraints) recovers a known motion from synthetic junction correspondences with outliers,
// starting from an odometry pose as wrong as a 6x-noisy odometry's over a few frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "backend/initialization/visual_constraints.h"
#include "frontend/matching/pair_refinement.h"

namespace sfm {
namespace {

TEST(RelativePoseFromMatches, RecoversTheRotationWithinATenthOfADegreeDespiteOutliers) {
  Eigen::Matrix3d K;
  K << 450, 0, 319.5, 0, 450, 239.5, 0, 0, 1;
  // A ground robot's step seen by a forward camera (y down): 0.3 m ahead, turning 0.05 rad.
  const Pose3 truth(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY())),
                    Eigen::Vector3d(0.02, 0.0, -0.3));
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> lateral(-3, 3), depth(2, 8), pixel_x(0, 639), pixel_y(0, 479);
    std::normal_distribution<double> location_noise(0, 0.5);
    std::vector<Eigen::Vector2d> x1, x2;
    while (x1.size() < 100) {
      const Eigen::Vector3d p1(lateral(rng), 0.5 * lateral(rng), depth(rng));
      const Eigen::Vector3d p2 = truth * p1;
      if (p2.z() < 0.5) continue;
      const Eigen::Vector3d u1 = K * p1, u2 = K * p2;
      const Eigen::Vector2d a = u1.head<2>() / u1.z(), b = u2.head<2>() / u2.z();
      if (b.x() < 0 || b.x() > 639 || b.y() < 0 || b.y() > 479) continue;
      x1.push_back(a + Eigen::Vector2d(location_noise(rng), location_noise(rng)));
      x2.push_back(b + Eigen::Vector2d(location_noise(rng), location_noise(rng)));
    }
    // A quarter of the correspondences wrong: junctions anywhere in image 2.
    for (int k = 0; k < 25; ++k) x2[static_cast<size_t>(4 * k)] = Eigen::Vector2d(pixel_x(rng), pixel_y(rng));

    // The odometry's pose: 0.03 rad and 5 cm off (a 6x odometry's heading error over a few frames),
    // with a covariance that admits the truth (0.02 rad and 0.05 m per axis).
    PairGeometry prior;
    prior.K = K;
    prior.camera2_T_camera1 =
        Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.03, Eigen::Vector3d(0.2, 1, 0).normalized())) * truth.rotation,
              truth.translation + Eigen::Vector3d(0.04, 0.0, 0.03));
    prior.covariance.setZero();
    prior.covariance.diagonal() << 4e-4, 4e-4, 4e-4, 2.5e-3, 2.5e-3, 2.5e-3;
    PairRefinementSettings settings;
    const PairRefinement map = RefinePairGeometry(prior, x1, x2, settings);
    ASSERT_TRUE(map.Refined()) << "seed " << seed << ": outcome " << static_cast<int>(map.outcome);
    const PairRefinement refinement = RelativePoseFromMatches(map, x1, x2, settings);
    ASSERT_TRUE(refinement.Refined()) << "seed " << seed << ": outcome " << static_cast<int>(refinement.outcome);
    const double error_deg =
        RotationAngle(refinement.geometry.camera2_T_camera1.rotation, truth.rotation) * 180 / M_PI;
    EXPECT_LT(error_deg, 0.1) << "seed " << seed;
    // The translation's direction too (its length is the prior's business): within 2 degrees
    // (observed 0.3-1.6).
    const double direction_deg =
        std::acos(std::clamp(refinement.geometry.camera2_T_camera1.translation.normalized().dot(
                                 truth.translation.normalized()),
                             -1.0, 1.0)) *
        180 / M_PI;
    EXPECT_LT(direction_deg, 2.0) << "seed " << seed;
    EXPECT_GE(refinement.inliers, 65) << "seed " << seed;
  }
}

}  // namespace
}  // namespace sfm

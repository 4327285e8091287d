// The pose drift's translation part (landmark_uncertainty.h) on hand-built cases with their figures.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/triangulation_options.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

Pose3 Forward(const Eigen::Vector3d& centre) { return Pose3(Eigen::Matrix3d::Identity(), centre); }

// Translation drift (PoseDrift::translation_step_m): the rectified stereo pair of
// PointSigmaAddsTheRelativeRotationDrift (wireframe_selection_test.cc), the second view k = 25
// frames after the first, the camera centres a random walk of 0.0006 m per axis per frame. The
// second centre relative to the first is off by 0.0006 sqrt(25) = 0.003 m along the baseline, which
// moves the point's x in that view by f 0.003 / Z = 0.3375 px (its offsets along y and z move the
// disparity by B / (2 Z) = 1/40 of that or not at all): sigma_Z = Z^2 / (f B) sqrt(2 sigma^2 +
// (f step / Z)^2 k) = 0.0964 m, against 0.0754 m from the pixels alone. To 2 %. The first view's
// centre is the common part, left out: frames 100 and 125 give the same. Fails without the
// translation term (0.0754) or with the error taken from frame 0 (0.0754 -> 0.24 m at frames
// 100, 125).
TEST(PoseDriftTest, PointSigmaAddsTheRelativeTranslationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0006;
  const int k = 25;
  const std::vector<Pose3> cameras = {Forward({-B / 2, 0, 0}), Forward({B / 2, 0, 0})};
  const double shift_px = f * step / Z;
  const double expected = Z * Z / (f * B) * std::sqrt(2 * sigma * sigma + shift_px * shift_px * k);
  PoseDrift drift;
  drift.translation_step_m = step;
  EXPECT_NEAR(expected, 0.0964, 0.0001);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {0, k}, {0, 0, Z}, sigma, drift), expected, 0.02 * expected);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, {100, 100 + k}, {0, 0, Z}, sigma, drift), expected,
              0.02 * expected);
}

// The vertical line of LineSigmaAddsTheRelativeRotationDrift with the same translation drift: at
// t = 1/2 each image line is off by sigma / sqrt(2) from its end-points, and the second centre's
// 0.003 m along the baseline moves its image line across itself by 0.3375 px: sigma_Z = Z^2 / (f B)
// sqrt(sigma^2 + (f step / Z)^2 k) = 0.0803 m (pixels alone 0.0533 m). To 2 %. Rotation and
// translation drift add as independent variances: both together give sqrt(0.0803^2 + 0.0962^2 -
// 0.0533^2).
TEST(PoseDriftTest, LineSigmaAddsTheRelativeTranslationDrift) {
  const double f = 450, B = 0.2, Z = 4, sigma = 0.3, step = 0.0006, rotation_step = 0.0002;
  const int k = 25;
  const Eigen::Matrix3d K = TestK();
  std::vector<LineSegmentView> views;
  for (const double x : {-B / 2, B / 2}) {
    const Pose3 camera = Forward({x, 0, 0});
    views.push_back({camera, Project(K, camera, {0, -0.5, Z}), Project(K, camera, {0, 0.5, Z}), x < 0 ? 3 : 3 + k});
  }
  const double shift_px = f * step / Z;
  const double translation = Z * Z / (f * B) * std::sqrt(sigma * sigma + shift_px * shift_px * k);
  const double rotation = Z * Z / (f * B) * std::sqrt(sigma * sigma + f * f * rotation_step * rotation_step * k);
  const double pixels = Z * Z / (f * B) * sigma;
  EXPECT_NEAR(translation, 0.0803, 0.0001);
  PoseDrift drift;
  drift.translation_step_m = step;
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma, drift), translation,
              0.02 * translation);
  drift.rotation_step_rad = rotation_step;
  const double both = std::sqrt(translation * translation + rotation * rotation - pixels * pixels);
  EXPECT_NEAR(LinePositionSigma(K, views, {0, 0, Z}, Eigen::Vector3d::UnitY(), sigma, drift), both, 0.02 * both);
}

TEST(PoseDriftTest, BadTranslationStepIsRejected) {
  WireframeOptions options;
  options.pose_translation_step_m = -1e-4;
  EXPECT_FALSE(options.Check().ok());
  options.pose_translation_step_m = std::nan("");
  EXPECT_FALSE(options.Check().ok());
}

}  // namespace
}  // namespace sfm

// PoseDrift::covariance (landmark_uncertainty.h): a vertex's sigma from a joint pose covariance,
// e.g. bundle adjustment's, in place of the fixed random walk.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "backend/triangulation/landmark_uncertainty.h"
#include "tests/triangulation/synthetic_cameras.h"

namespace sfm {
namespace {

using testing::Project;
using testing::TestK;

// A PoseCovariance whose cameras look along +z from `centres` (no lever arm), every frame's
// translation a random walk of `step` m per axis per frame from frame 0 (Cov(y_f, y_g) = min(f, g)
// step^2), rotations exact.
std::shared_ptr<PoseCovariance> TranslationRandomWalk(const std::vector<Eigen::Vector3d>& centres,
                                                      double step) {
  auto covariance = std::make_shared<PoseCovariance>();
  const int n = static_cast<int>(centres.size());
  covariance->camera_R_world.assign(n, Eigen::Matrix3d::Identity());
  covariance->centre = centres;
  covariance->lever.assign(n, Eigen::Vector3d::Zero());
  covariance->tangent = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (int f = 0; f < n; ++f) {
    for (int g = 0; g < n; ++g) {
      covariance->tangent.block<3, 3>(6 * f + 3, 6 * g + 3) =
          std::min(f, g) * step * step * Eigen::Matrix3d::Identity();
    }
  }
  return covariance;
}

// With rotations exact and no lever arm a view's centre error relative to the first view f0 is
// dt_i - dt_f0, whose covariance for a random walk is min(f_i - f0, f_j - f0) step^2: the joint
// covariance must give exactly PoseDrift's translation random walk. Five views of a point 4 m
// away and of a line through it, spread over frames 10-40 of a 0.1 m-per-frame sideways path,
// the walk 0.002 m per axis per frame (large enough to dominate the pixel term: 0.0754 m -> more
// than twice). Equal to 1e-9 relative for the point and for both line directions; the pose part
// must not vanish either (the sigma at least 1.5 x the pixels' alone). Fails if the gains are
// paired with the wrong frames, if the anchor's own error is counted, or if f0's row is dropped.
TEST(PoseCovarianceDriftTest, EqualsTheRandomWalkItGeneralises) {
  const double sigma = 0.3, step = 0.002;
  const std::vector<int> frames = {10, 16, 25, 33, 40};
  std::vector<Eigen::Vector3d> centres;
  for (int f = 0; f < 50; ++f) centres.emplace_back(0.1 * f - 2.5, 0.02 * f, 0);
  std::vector<Pose3> cameras;
  for (int f : frames) cameras.emplace_back(Eigen::Quaterniond::Identity(), centres[f]);
  const Eigen::Vector3d point(0.2, -0.3, 4);
  PoseDrift walk;
  walk.translation_step_m = step;
  PoseDrift joint;
  joint.covariance = TranslationRandomWalk(centres, step);
  const Eigen::Matrix3d K = TestK();
  const double pixels = PointPositionSigma(K, cameras, point, sigma);
  const double expected = PointPositionSigma(K, cameras, frames, point, sigma, walk);
  EXPECT_GT(expected, 1.5 * pixels);
  EXPECT_NEAR(PointPositionSigma(K, cameras, frames, point, sigma, joint), expected, 1e-9 * expected);

  const Eigen::Vector3d direction = Eigen::Vector3d(0.3, 1, 0.2).normalized();
  std::vector<LineSegmentView> views;
  for (size_t i = 0; i < frames.size(); ++i) {
    views.push_back({cameras[i], Project(K, cameras[i], point - 0.4 * direction),
                     Project(K, cameras[i], point + 0.6 * direction), frames[i]});
  }
  const double line_expected = LinePositionSigma(K, views, point, direction, sigma, walk);
  EXPECT_GT(line_expected, 1.5 * LinePositionSigma(K, views, point, direction, sigma));
  EXPECT_NEAR(LinePositionSigma(K, views, point, direction, sigma, joint), line_expected,
              1e-9 * line_expected);
}

// The rigid part common to a landmark's views is left out: a covariance in which every frame has
// the same (fully correlated) rotation and translation error moves the whole reconstruction
// rigidly with frame f0, so it adds nothing to a vertex's sigma (to 1e-9 relative), where the
// random walk of the same per-frame size would add. Protects Anchor's delta_0 x (c_i - c_0) term:
// without it a common rotation would show up as centre errors of the other views.
TEST(PoseCovarianceDriftTest, ACommonRigidErrorAddsNothing) {
  const double sigma = 0.3;
  const std::vector<int> frames = {2, 5, 9};
  std::vector<Eigen::Vector3d> centres;
  for (int f = 0; f < 12; ++f) centres.emplace_back(0.15 * f - 1, 0, 0.05 * f);
  auto covariance = std::make_shared<PoseCovariance>();
  covariance->camera_R_world.assign(12, Eigen::Matrix3d::Identity());
  covariance->centre = centres;
  covariance->lever.assign(12, Eigen::Vector3d::Zero());
  // One rigid error (rotation delta about the world origin, translation dt) for all frames: each
  // frame's base translation moves by delta x t_f + dt, y_f = J_f (delta, dt).
  Eigen::MatrixXd J(6 * 12, 6);
  for (int f = 0; f < 12; ++f) {
    J.block<3, 3>(6 * f, 0).setIdentity();
    J.block<3, 3>(6 * f, 3).setZero();
    Eigen::Matrix3d cross;
    const Eigen::Vector3d& t = centres[f];
    cross << 0, t.z(), -t.y(), -t.z(), 0, t.x(), t.y(), -t.x(), 0;  // delta x t = -[t]x delta
    J.block<3, 3>(6 * f + 3, 0) = cross;
    J.block<3, 3>(6 * f + 3, 3).setIdentity();
  }
  covariance->tangent = J * (0.01 * 0.01) * J.transpose();
  std::vector<Pose3> cameras;
  for (int f : frames) cameras.emplace_back(Eigen::Quaterniond::Identity(), centres[f]);
  const Eigen::Vector3d point(0.1, 0.2, 3);
  PoseDrift joint;
  joint.covariance = covariance;
  const double pixels = PointPositionSigma(TestK(), cameras, point, sigma);
  EXPECT_NEAR(PointPositionSigma(TestK(), cameras, frames, point, sigma, joint), pixels, 1e-9 * pixels);
  PoseDrift walk;
  walk.rotation_step_rad = 0.01;
  walk.translation_step_m = 0.01;
  EXPECT_GT(PointPositionSigma(TestK(), cameras, frames, point, sigma, walk), 2 * pixels);
}

}  // namespace
}  // namespace sfm

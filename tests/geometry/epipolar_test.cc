#include "geometry/epipolar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace sfm {
namespace {

// A measured figure for the test report (gtest XML), in scientific notation.
std::string Figure(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3e", value);
  return text;
}

Eigen::Matrix3d TestK() {
  Eigen::Matrix3d K;
  K << 520, 0, 318.6, 0, 515, 245.3, 0, 0, 1;
  return K;
}

Eigen::Vector2d ProjectK(const Eigen::Matrix3d& K, const Pose3& world_T_camera, const Eigen::Vector3d& p_world) {
  const Eigen::Vector3d p_camera = world_T_camera.Inverse() * p_world;
  return (K * p_camera).hnormalized();
}

// Points a few metres in front of both test cameras.
std::vector<Eigen::Vector3d> ScenePoints() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 100; ++i) points.push_back(Eigen::Vector3d::Random() * 1.5 + Eigen::Vector3d(0, 0, 5));
  return points;
}

// Largest distance, both ways, between a projected point and the epipolar line of its partner.
double MaxEpipolarError(const Eigen::Matrix3d& F, const Eigen::Matrix3d& K, const Pose3& world_T_camera1,
                        const Pose3& world_T_camera2) {
  double max_error = 0;
  for (const Eigen::Vector3d& p : ScenePoints()) {
    const Eigen::Vector2d x1 = ProjectK(K, world_T_camera1, p), x2 = ProjectK(K, world_T_camera2, p);
    max_error = std::max({max_error, PointLineDistance(EpipolarLineInImage2(F, x1), x2),
                          PointLineDistance(EpipolarLineInImage1(F, x2), x1)});
  }
  return max_error;
}

const Pose3 kWorldTCamera1(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 2, 3).normalized())),
                           Eigen::Vector3d(0.2, -0.1, 0.05));
const Pose3 kWorldTCamera2(Eigen::Quaterniond(Eigen::AngleAxisd(-0.15, Eigen::Vector3d(-1, 3, 0.5).normalized())),
                           Eigen::Vector3d(0.9, 0.15, -0.3));

TEST(EpipolarTest, FundamentalFromPosesPointToLineBelow1e6Pixels) {
  const Eigen::Matrix3d F = FundamentalFromPoses(TestK(), kWorldTCamera1, kWorldTCamera2);
  const double error = MaxEpipolarError(F, TestK(), kWorldTCamera1, kWorldTCamera2);
  RecordProperty("max_error_px", Figure(error));
  EXPECT_LT(error, 1e-6);
}

TEST(EpipolarTest, FundamentalFromOdometryWithMountedCameraPointToLineBelow1e6Pixels) {
  // A camera looking sideways and down from a mast: the mounting matters to F.
  const Pose3 base_T_camera(Eigen::Matrix3d(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()) *
                                            Eigen::AngleAxisd(-M_PI / 2 - 0.2, Eigen::Vector3d::UnitX())),
                            Eigen::Vector3d(0.3, -0.1, 1.2));
  const Pose3 world_T_base1 = kWorldTCamera1 * base_T_camera.Inverse();
  const Pose3 world_T_base2 = kWorldTCamera2 * base_T_camera.Inverse();
  const Eigen::Matrix3d F = FundamentalFromOdometry(TestK(), base_T_camera, world_T_base1, world_T_base2);
  const double error =
      MaxEpipolarError(F, TestK(), world_T_base1 * base_T_camera, world_T_base2 * base_T_camera);
  RecordProperty("max_error_px", Figure(error));
  EXPECT_LT(error, 1e-6);
  // Ignoring the mounting gives a different, wrong F.
  const Eigen::Matrix3d F_unmounted = FundamentalFromPoses(TestK(), world_T_base1, world_T_base2);
  EXPECT_GT(MaxEpipolarError(F_unmounted, TestK(), kWorldTCamera1, kWorldTCamera2), 1.0);
}

TEST(EpipolarTest, FundamentalFromProjectionsPointToLineBelow1e6Pixels) {
  // VGG-style matrices carry an arbitrary scale; F must not depend on it.
  const Eigen::Matrix<double, 3, 4> P1 = 3.7 * TestK() * kWorldTCamera1.Inverse().Matrix3x4();
  const Eigen::Matrix<double, 3, 4> P2 = -0.02 * TestK() * kWorldTCamera2.Inverse().Matrix3x4();
  const Eigen::Matrix3d F = FundamentalFromProjections(P1, P2);
  const double error = MaxEpipolarError(F, TestK(), kWorldTCamera1, kWorldTCamera2);
  RecordProperty("max_error_px", Figure(error));
  EXPECT_LT(error, 1e-6);
  // Same F as from the poses, up to scale and sign.
  const Eigen::Matrix3d F_poses = FundamentalFromPoses(TestK(), kWorldTCamera1, kWorldTCamera2).normalized();
  const Eigen::Matrix3d F_normalised = F.normalized();
  EXPECT_LT(std::min((F_normalised - F_poses).norm(), (F_normalised + F_poses).norm()), 1e-9);
}

TEST(EpipolarTest, PointLineDistanceOfKnownLineExact) {
  EXPECT_DOUBLE_EQ(PointLineDistance(Eigen::Vector3d(2, 0, -10), Eigen::Vector2d(8, 2)), 3.0);
  EXPECT_DOUBLE_EQ(PointLineDistance(Eigen::Vector3d(3, 4, 0), Eigen::Vector2d(3, 4)), 5.0);
  EXPECT_EQ(PointLineDistance(Eigen::Vector3d(0, 0, 1), Eigen::Vector2d(1, 1)),
            std::numeric_limits<double>::infinity());
}

TEST(EpipolarTest, SymmetricDistanceOfRectifiedPairIsTheRowOffsetTo1e9) {
  // Sideways translation with equal K: epipolar lines are image rows.
  const Pose3 world_T_camera2(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, 0, 0));
  const Eigen::Matrix3d F = FundamentalFromPoses(TestK(), Pose3::Identity(), world_T_camera2);
  EXPECT_NEAR(SymmetricEpipolarDistance(F, Eigen::Vector2d(100, 200), Eigen::Vector2d(40, 202.5)), 2.5, 1e-9);
  EXPECT_NEAR(SymmetricEpipolarDistance(F, Eigen::Vector2d(100, 200), Eigen::Vector2d(300, 200)), 0.0, 1e-9);
}

}  // namespace
}  // namespace sfm

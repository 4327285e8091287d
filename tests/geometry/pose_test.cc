#include "geometry/pose.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sfm {
namespace {

Pose3 RandomPose() {
  return Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random() * 5);
}

TEST(Pose3Test, CompositionChainsFramesTo1e12) {
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 a_T_b = RandomPose(), b_T_c = RandomPose();
    const Eigen::Vector3d p_c = Eigen::Vector3d::Random();
    EXPECT_LT(((a_T_b * b_T_c) * p_c - a_T_b * (b_T_c * p_c)).norm(), 1e-12);
    EXPECT_LT(((a_T_b * b_T_c).Matrix4() - a_T_b.Matrix4() * b_T_c.Matrix4()).norm(), 1e-12);
  }
}

TEST(Pose3Test, InverseUndoesThePoseTo1e12) {
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 a_T_b = RandomPose();
    const Pose3 identity = a_T_b * a_T_b.Inverse();
    EXPECT_LT(identity.translation.norm(), 1e-12);
    EXPECT_LT(RotationAngle(identity.rotation, Eigen::Quaterniond::Identity()), 1e-12);
    const Eigen::Vector3d p_b = Eigen::Vector3d::Random();
    EXPECT_LT((a_T_b.Inverse() * (a_T_b * p_b) - p_b).norm(), 1e-12);
    EXPECT_LT((a_T_b.Inverse().Matrix4() - a_T_b.Matrix4().inverse()).norm(), 1e-12);
  }
}

TEST(Pose3Test, Matrix4RoundTripTo1e12) {
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 pose = RandomPose();
    const Pose3 back = Pose3::FromMatrix4(pose.Matrix4());
    EXPECT_LT(RotationAngle(back.rotation, pose.rotation), 1e-12);
    EXPECT_LT((back.translation - pose.translation).norm(), 1e-12);
    EXPECT_LT((back.Matrix4() - pose.Matrix4()).norm(), 1e-12);
    EXPECT_LT((pose.Matrix3x4() - pose.Matrix4().topRows<3>()).norm(), 1e-15);
  }
}

TEST(Pose3Test, RotationAngleOfAKnownRotationTo1e12) {
  const Eigen::Quaterniond a(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond b(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(RotationAngle(a, b), 0.7, 1e-12);
  // q and -q are the same rotation.
  EXPECT_NEAR(RotationAngle(a, Eigen::Quaterniond(-a.coeffs())), 0.0, 1e-7);
}

}  // namespace
}  // namespace sfm

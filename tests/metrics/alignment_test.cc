#include "backend/metrics/alignment.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sfm {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int count, double half_extent) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) points.push_back(Eigen::Vector3d::Random() * half_extent);
  return points;
}

std::vector<Eigen::Vector3d> Transformed(const Pose3& T, const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : points) out.push_back(T * p);
  return out;
}

TEST(AlignSE3Test, RecoversARandomRigidTransformTo1e9) {
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 truth_T_estimated(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random() * 50);
    const std::vector<Eigen::Vector3d> estimated = RandomPoints(3 + trial, 10);
    bool rotation_determined = false;
    const Pose3 T = AlignSE3(estimated, Transformed(truth_T_estimated, estimated), &rotation_determined);
    EXPECT_TRUE(rotation_determined);
    EXPECT_LT(RotationAngle(T.rotation, truth_T_estimated.rotation), /*max_rad=*/1e-9);
    EXPECT_LT((T.translation - truth_T_estimated.translation).norm(), /*max_m=*/1e-9);
  }
}

TEST(AlignSE3Test, RecoversTheRotationOfAPlanarSet) {
  // Planar points give a rank-2 cross-covariance: the reflection fix picks the proper rotation.
  std::vector<Eigen::Vector3d> estimated;
  for (int i = 0; i < 10; ++i) estimated.push_back(Eigen::Vector3d(Eigen::Vector2d::Random().x(), i, 0));
  const Pose3 truth_T_estimated(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(1, -2, 3));
  bool rotation_determined = false;
  const Pose3 T = AlignSE3(estimated, Transformed(truth_T_estimated, estimated), &rotation_determined);
  EXPECT_TRUE(rotation_determined);
  EXPECT_LT(RotationAngle(T.rotation, truth_T_estimated.rotation), 1e-9);
  EXPECT_LT((T.translation - truth_T_estimated.translation).norm(), 1e-9);
}

TEST(AlignSE3Test, AMirroredSetGetsAProperRotation) {
  // No rotation maps a set onto its mirror image; the best rigid fit must still be a rotation.
  const std::vector<Eigen::Vector3d> estimated = RandomPoints(8, 5);
  std::vector<Eigen::Vector3d> mirrored;
  for (const Eigen::Vector3d& p : estimated) mirrored.push_back(Eigen::Vector3d(-p.x(), p.y(), p.z()));
  const Pose3 T = AlignSE3(estimated, mirrored);
  EXPECT_NEAR(T.RotationMatrix().determinant(), 1.0, 1e-12);
}

TEST(AlignSE3Test, NoPointGivesTheIdentity) {
  bool rotation_determined = true;
  const Pose3 T = AlignSE3({}, {}, &rotation_determined);
  EXPECT_FALSE(rotation_determined);
  EXPECT_EQ(T.translation, Eigen::Vector3d::Zero());
  EXPECT_EQ(T.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
}

TEST(AlignSE3Test, OneOrTwoPointsGiveTranslationOnly) {
  const Pose3 rotated(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d(4, 5, 6));
  for (const int count : {1, 2}) {
    const std::vector<Eigen::Vector3d> estimated = RandomPoints(count, 3);
    const std::vector<Eigen::Vector3d> truth = Transformed(rotated, estimated);
    bool rotation_determined = true;
    const Pose3 T = AlignSE3(estimated, truth, &rotation_determined);
    EXPECT_FALSE(rotation_determined);
    EXPECT_EQ(T.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
    Eigen::Vector3d centroid_offset = Eigen::Vector3d::Zero();
    for (int i = 0; i < count; ++i) centroid_offset += (truth[i] - estimated[i]) / count;
    EXPECT_LT((T.translation - centroid_offset).norm(), 1e-12);
  }
}

TEST(AlignSE3Test, CollinearPointsGiveTranslationOnly) {
  const Eigen::Vector3d direction = Eigen::Vector3d(1, 2, -0.5).normalized();
  std::vector<Eigen::Vector3d> estimated;
  for (int i = 0; i < 6; ++i) estimated.push_back(Eigen::Vector3d(3, 1, 2) + 0.7 * i * direction);
  const std::vector<Eigen::Vector3d> truth =
      Transformed(Pose3(Eigen::Matrix3d::Identity(), {1, 1, 1}), estimated);
  bool rotation_determined = true;
  const Pose3 T = AlignSE3(estimated, truth, &rotation_determined);
  EXPECT_FALSE(rotation_determined);
  EXPECT_LT((T.translation - Eigen::Vector3d(1, 1, 1)).norm(), 1e-12);
}

}  // namespace
}  // namespace sfm

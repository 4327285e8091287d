#include "geometry/alignment.h"

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

TEST(AlignSim3Test, RecoversARandomSimilarityTo1e9) {
  for (int trial = 0; trial < 20; ++trial) {
    Similarity3 truth_S_estimated;
    truth_S_estimated.scale = 0.5 + trial * 0.1;
    truth_S_estimated.rigid = Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random() * 50);
    const std::vector<Eigen::Vector3d> estimated = RandomPoints(3 + trial, 10);
    std::vector<Eigen::Vector3d> truth;
    for (const Eigen::Vector3d& p : estimated) truth.push_back(truth_S_estimated * p);
    bool rotation_determined = false;
    const Similarity3 S = AlignSim3(estimated, truth, &rotation_determined);
    EXPECT_TRUE(rotation_determined);
    EXPECT_NEAR(S.scale, truth_S_estimated.scale, /*max=*/1e-9);
    EXPECT_LT(RotationAngle(S.rigid.rotation, truth_S_estimated.rigid.rotation), /*max_rad=*/1e-9);
    EXPECT_LT((S.rigid.translation - truth_S_estimated.rigid.translation).norm(), /*max_m=*/1e-9);
  }
}

TEST(AlignSim3Test, ScaleOfAHandBuiltPairIsTheRatioOfSpreads) {
  // Two points 2 m apart against the same two 4 m apart (rotation undetermined, translation-only
  // case): the least-squares scale is tr(Sigma) / sigma_e^2 = 2 / 1 and maps them exactly.
  const std::vector<Eigen::Vector3d> estimated = {{-1, 0, 0}, {1, 0, 0}};
  const std::vector<Eigen::Vector3d> truth = {{3, 5, 0}, {7, 5, 0}};
  const Similarity3 S = AlignSim3(estimated, truth);
  EXPECT_NEAR(S.scale, 2.0, 1e-12);
  EXPECT_LT((S * estimated[0] - truth[0]).norm(), 1e-12);
  EXPECT_LT((S * estimated[1] - truth[1]).norm(), 1e-12);
}

TEST(AlignSim3Test, CoincidentPointsKeepScaleOne) {
  const std::vector<Eigen::Vector3d> estimated = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  const std::vector<Eigen::Vector3d> truth = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(AlignSim3(estimated, truth).scale, 1.0);
  EXPECT_EQ(AlignSim3({}, {}).scale, 1.0);
}

}  // namespace
}  // namespace sfm

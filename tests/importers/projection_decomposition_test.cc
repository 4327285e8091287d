#include "sequences/importers/projection_decomposition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace sfm {
namespace {

using ::testing::HasSubstr;

// A camera with every intrinsic nonzero (skew too) and a rotation about an oblique axis.
struct KnownCamera {
  Eigen::Matrix3d K;
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  Eigen::Matrix<double, 3, 4> P(double lambda) const {
    Eigen::Matrix<double, 3, 4> Rt;
    Rt << R, t;
    return lambda * K * Rt;
  }
};

KnownCamera MakeCamera() {
  KnownCamera camera;
  camera.K << 512.5, 7.25, 301.75, 0, 498.125, 255.5, 0, 0, 1;
  camera.R = Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -1, 0.6).normalized()).toRotationMatrix();
  camera.t = Eigen::Vector3d(0.4, -1.7, 5.25);
  return camera;
}

void ExpectRecovers(const KnownCamera& camera, double lambda) {
  ProjectionDecomposition decomposition;
  ASSERT_TRUE(DecomposeProjection(camera.P(lambda), &decomposition).ok());
  EXPECT_LT((decomposition.K - camera.K).cwiseAbs().maxCoeff() / camera.K.norm(), 1e-12) << decomposition.K;
  EXPECT_LT((decomposition.camera_T_world.RotationMatrix() - camera.R).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((decomposition.camera_T_world.translation - camera.t).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((decomposition.centre - (-camera.R.transpose() * camera.t)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ProjectionDecompositionTest, RecoversKnownCameraToOneNanoForAnyScale) {
  const KnownCamera camera = MakeCamera();
  ExpectRecovers(camera, 1.0);
  ExpectRecovers(camera, 3.7e-3);  // a P normalised some other way
}

TEST(ProjectionDecompositionTest, RecoversKnownCameraFromNegatedP) {
  // P and -P are the same camera; the VGG files hold the negative one.
  const KnownCamera camera = MakeCamera();
  ExpectRecovers(camera, -1.0);
  ExpectRecovers(camera, -250.0);
}

TEST(ProjectionDecompositionTest, RecoversIdentityRotationAndNegativeSkew) {
  KnownCamera camera = MakeCamera();
  camera.R.setIdentity();
  camera.K(0, 1) = -17.4;
  ExpectRecovers(camera, -2.0);
}

TEST(ProjectionDecompositionTest, RejectsSingularAndNonFiniteP) {
  ProjectionDecomposition decomposition;
  Eigen::Matrix<double, 3, 4> P = MakeCamera().P(1.0);
  P.row(2) = P.row(1);  // the left block loses rank
  const Status singular = DecomposeProjection(P, &decomposition);
  EXPECT_THAT(singular.message(), HasSubstr("singular"));
  P = MakeCamera().P(1.0);
  P(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(DecomposeProjection(P, &decomposition).message(), HasSubstr("non-finite"));
}

}  // namespace
}  // namespace sfm

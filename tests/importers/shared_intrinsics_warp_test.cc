#include "sequences/importers/shared_intrinsics_warp.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace sfm {
namespace {

using ::testing::HasSubstr;

Eigen::Matrix3d Intrinsics(double fx, double fy, double cx, double cy, double skew) {
  Eigen::Matrix3d K;
  K << fx, skew, cx, 0, fy, cy, 0, 0, 1;
  return K;
}

Eigen::Vector2d Apply(const Eigen::Matrix<double, 2, 3>& A, const Eigen::Vector2d& x) {
  return A * x.homogeneous();
}

// Intrinsics that vary as the VGG Corridor's do (fx 495-518, cx 271-359, skew up to 17 px).
std::vector<Eigen::Matrix3d> CorridorLikeIntrinsics() {
  return {Intrinsics(495, 497, 271, 251, 0), Intrinsics(503, 506, 295, 266, 5),
          Intrinsics(518, 528, 359, 280, 17), Intrinsics(510, 512, 320, 259, -8)};
}

// The point of the warp: a point seen by K_i [R | t] lands, after frame i's map, where the shared
// K [R | t] of the crop sees it. Exact up to rounding (tolerance 1e-9 px).
TEST(SharedIntrinsicsWarpTest, MapsEachFramesProjectionsOntoTheSharedCamera) {
  const std::vector<Eigen::Matrix3d> frame_K = CorridorLikeIntrinsics();
  const Eigen::Matrix3d shared = Intrinsics(505, 509, 300, 262, 0);
  SharedIntrinsicsWarp warp;
  ASSERT_TRUE(WarpToSharedIntrinsics(frame_K, 512, 512, shared, &warp).ok());
  ASSERT_EQ(warp.source_to_image.size(), frame_K.size());
  EXPECT_DOUBLE_EQ(warp.K(0, 0), 505);
  EXPECT_DOUBLE_EQ(warp.K(1, 1), 509);
  EXPECT_EQ(warp.K(0, 1), 0);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, -0.1).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.4, -0.2, 1.5);
  for (size_t i = 0; i < frame_K.size(); ++i) {
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector3d X(std::sin(k) * 2, std::cos(1.7 * k), 6 + 3 * std::sin(0.3 * k));
      const Eigen::Vector3d camera = R * X + t;
      const Eigen::Vector2d source = (frame_K[i] * camera).hnormalized();
      const Eigen::Vector2d shared_pixel = (warp.K * camera).hnormalized();
      EXPECT_LT((Apply(warp.source_to_image[i], source) - shared_pixel).norm(), 1e-9) << "frame " << i;
    }
  }
}

// Every pixel of the crop reads its frame's image at least the interpolation margin inside it, so
// no frame gets a border of fill; and the crop is not needlessly small: with one K for every frame
// it is the whole image less the margin.
TEST(SharedIntrinsicsWarpTest, CropLiesInsideEveryFrameAndIsWholeWhenTheKsAgree) {
  const std::vector<Eigen::Matrix3d> frame_K = CorridorLikeIntrinsics();
  SharedIntrinsicsWarp warp;
  ASSERT_TRUE(WarpToSharedIntrinsics(frame_K, 512, 512, Intrinsics(505, 509, 300, 262, 0), &warp).ok());
  EXPECT_GT(warp.width * warp.height, 512 * 512 / 2);  // cx spans 88 px, fx 5 %: most of the image is left
  for (size_t i = 0; i < frame_K.size(); ++i) {
    const Eigen::Matrix3d A = (Eigen::Matrix3d() << warp.source_to_image[i], 0, 0, 1).finished();
    const Eigen::Matrix3d image_to_source = A.inverse();
    for (const Eigen::Vector2d& corner :
         {Eigen::Vector2d(0, 0), Eigen::Vector2d(warp.width - 1, 0), Eigen::Vector2d(0, warp.height - 1),
          Eigen::Vector2d(warp.width - 1, warp.height - 1)}) {
      const Eigen::Vector2d source = (image_to_source * corner.homogeneous()).hnormalized();
      EXPECT_GE(source.minCoeff(), kWarpInterpolationMargin - 1e-9) << "frame " << i;
      EXPECT_LE(source.maxCoeff(), 511 - kWarpInterpolationMargin + 1e-9) << "frame " << i;
    }
  }
  const Eigen::Matrix3d K = Intrinsics(400, 400, 160, 120, 0);
  ASSERT_TRUE(WarpToSharedIntrinsics({K, K, K}, 320, 240, K, &warp).ok());
  EXPECT_EQ(warp.width, 318);
  EXPECT_EQ(warp.height, 238);
  EXPECT_DOUBLE_EQ(warp.K(0, 2), 159);
  EXPECT_DOUBLE_EQ(warp.K(1, 2), 119);
}

TEST(SharedIntrinsicsWarpTest, RefusesIntrinsicsThatShareTooLittleOfTheImage) {
  SharedIntrinsicsWarp warp;
  const Status status =
      WarpToSharedIntrinsics({Intrinsics(500, 500, 50, 256, 0), Intrinsics(500, 500, 450, 256, 0)}, 512, 512,
                             Intrinsics(500, 500, 256, 256, 0), &warp);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr("less than a quarter"));
  Eigen::Matrix3d not_upper = Intrinsics(500, 500, 256, 256, 0);
  not_upper(1, 0) = 1;
  EXPECT_FALSE(WarpToSharedIntrinsics({not_upper}, 512, 512, Intrinsics(500, 500, 256, 256, 0), &warp).ok());
}

}  // namespace
}  // namespace sfm

// Images of one camera position with different intrinsics, resampled to one shared K.
//
// A camera P_i = K_i [R_i | t_i] and a camera K [R_i | t_i] at the same centre see the same rays,
// so their images differ by the homography H_i = K K_i^-1 (Hartley and Zisserman, "Multiple View
// Geometry", 2nd ed., section 8.4: cameras with a common centre map by x' = K' R K^-1 x, here
// R = I). With K_i and K upper triangular H_i is affine. Warping image i by H_i makes it an image
// of K [R_i | t_i] exactly: the pose of each P's own decomposition then is the true pose for the
// shared K, with no refit. The warped images are cropped to the largest axis-aligned rectangle that every
// warped image covers completely, so that no frame has a border of fill (which would be edges).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "util/status.h"

namespace sfm {

struct SharedIntrinsicsWarp {
  Eigen::Matrix3d K =
      Eigen::Matrix3d::Identity();  // of the cropped images: the shared K, principal point moved
  int width = 0, height = 0;        // of the cropped images, pixels
  // Per frame: sequence pixel = A (source pixel; 1), both in OpenCV's pixel-centre convention.
  std::vector<Eigen::Matrix<double, 2, 3>> source_to_image;
};

// Pixels of a source image at most this far inside its border are left out of the crop, so that
// the resampling (bicubic: a 4 x 4 support about the sample) never reads past the image.
constexpr double kWarpInterpolationMargin = 1.0;

// Warps for frames of `width` x `height` pixels with intrinsics `frame_K` (upper triangular, K(2,2)
// = 1, skew allowed) onto `shared_K` (zero skew expected, not required), cropped as above within the
// canvas of `shared_K`'s own width x height image. Fails when a K is not upper triangular with a
// positive diagonal, or when the warped images have no common rectangle of at least a quarter of
// the source area (intrinsics that far apart are not one camera's).
Status WarpToSharedIntrinsics(const std::vector<Eigen::Matrix3d>& frame_K, int width, int height,
                              const Eigen::Matrix3d& shared_K, SharedIntrinsicsWarp* warp);

}  // namespace sfm

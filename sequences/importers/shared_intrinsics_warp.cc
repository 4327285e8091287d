#include "sequences/importers/shared_intrinsics_warp.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <string>

namespace sfm {
namespace {

bool IsIntrinsicMatrix(const Eigen::Matrix3d& K) {
  return K.allFinite() && K(1, 0) == 0 && K(2, 0) == 0 && K(2, 1) == 0 && K(2, 2) == 1 && K(0, 0) > 0 &&
         K(1, 1) > 0;
}

struct Rectangle {
  int x = 0, y = 0, width = 0, height = 0;
  long Area() const { return static_cast<long>(width) * height; }
};

// The largest axis-aligned rectangle of true cells of a row-major mask (the histogram-and-stack
// method: per row, the heights of the true columns above it; per row, the largest rectangle under
// that histogram). Ties go to the first found, so the result does not depend on anything but the mask.
Rectangle LargestRectangle(const std::vector<char>& mask, int width, int height) {
  std::vector<int> heights(width + 1, 0);  // a zero sentinel column at the end empties the stack
  std::vector<int> stack;
  Rectangle best;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      heights[x] = mask[static_cast<size_t>(y) * width + x] ? heights[x] + 1 : 0;
    stack.clear();
    for (int x = 0; x <= width; ++x) {
      while (!stack.empty() && heights[stack.back()] >= heights[x]) {
        const int h = heights[stack.back()];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        const Rectangle candidate{left, y - h + 1, x - left, h};
        if (candidate.Area() > best.Area()) best = candidate;
      }
      stack.push_back(x);
    }
  }
  return best;
}

}  // namespace

Status WarpToSharedIntrinsics(const std::vector<Eigen::Matrix3d>& frame_K, int width, int height,
                              const Eigen::Matrix3d& shared_K, SharedIntrinsicsWarp* warp) {
  if (width < 4 || height < 4)
    return Status::Error("shared-K warp: images of " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels are too small");
  if (!IsIntrinsicMatrix(shared_K))
    return Status::Error("shared-K warp: the shared K is not an intrinsic matrix");
  // Canvas pixel -> source pixel of each frame: K_i K^-1 (the inverse of H_i = K K_i^-1).
  std::vector<Eigen::Matrix3d> canvas_to_source;
  for (size_t i = 0; i < frame_K.size(); ++i) {
    if (!IsIntrinsicMatrix(frame_K[i])) {
      return Status::Error("shared-K warp: frame " + std::to_string(i) +
                           "'s K is not upper triangular with a "
                           "positive diagonal");
    }
    canvas_to_source.push_back(frame_K[i] * shared_K.inverse());
  }
  // A canvas pixel is usable when every frame's source position lies at least the interpolation
  // margin inside that frame's image.
  const double low = kWarpInterpolationMargin;
  const double high_x = width - 1 - kWarpInterpolationMargin, high_y = height - 1 - kWarpInterpolationMargin;
  std::vector<char> mask(static_cast<size_t>(width) * height, 1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (const Eigen::Matrix3d& M : canvas_to_source) {
        const Eigen::Vector2d source = (M * Eigen::Vector3d(x, y, 1)).hnormalized();
        if (source.x() < low || source.y() < low || source.x() > high_x || source.y() > high_y) {
          mask[static_cast<size_t>(y) * width + x] = 0;
          break;
        }
      }
    }
  }
  const Rectangle crop = LargestRectangle(mask, width, height);
  if (4 * crop.Area() < static_cast<long>(width) * height) {
    return Status::Error("shared-K warp: the warped images share a rectangle of only " +
                         std::to_string(crop.width) + "x" + std::to_string(crop.height) +
                         " pixels, less than a quarter of the " + std::to_string(width) + "x" +
                         std::to_string(height) + " images");
  }
  SharedIntrinsicsWarp result;
  result.K = shared_K;
  result.K(0, 2) -= crop.x;
  result.K(1, 2) -= crop.y;
  result.width = crop.width;
  result.height = crop.height;
  for (const Eigen::Matrix3d& K_i : frame_K) {
    // Source pixel -> cropped pixel: the crop's translation after H_i = K K_i^-1, i.e. K_crop K_i^-1.
    const Eigen::Matrix3d H = result.K * K_i.inverse();
    result.source_to_image.push_back(H.topRows<2>() / H(2, 2));
  }
  *warp = std::move(result);
  return Status::Ok();
}

}  // namespace sfm

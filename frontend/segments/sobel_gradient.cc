#include "frontend/segments/sobel_gradient.h"

#include <glog/logging.h>

#include <algorithm>
#include <cstdlib>

namespace sfm {
namespace {

// One row from the image rows above, at and below it (replicated at the border rows); `low` is
// INT16_MAX on the border rows. Branch-free, so that GCC vectorises it. The restrict parameters
// matter: without them the byte loads might alias the stores, and GCC gives up after too many
// run-time alias checks (the same loop on plain pointers ran scalar, about 4 x the instructions).
void SobelRow(const uint8_t* __restrict up, const uint8_t* __restrict mid, const uint8_t* __restrict down,
              int cols, int16_t low, int16_t* __restrict dx, int16_t* __restrict dy, int16_t* __restrict mag,
              uint8_t* __restrict dir) {
  // Interior columns; the two border columns below, with x - 1 or x + 1 replicated.
  for (int x = 1; x + 1 < cols; ++x) {
    const int16_t gx = static_cast<int16_t>((up[x + 1] - up[x - 1]) + 2 * (mid[x + 1] - mid[x - 1]) +
                                            (down[x + 1] - down[x - 1]));
    const int16_t gy =
        static_cast<int16_t>((down[x - 1] - up[x - 1]) + 2 * (down[x] - up[x]) + (down[x + 1] - up[x + 1]));
    dx[x] = gx;
    dy[x] = gy;
    const int16_t ax = static_cast<int16_t>(std::abs(gx)), ay = static_cast<int16_t>(std::abs(gy));
    const int16_t m = static_cast<int16_t>(ax + ay);
    mag[x] = m;
    // m >= low ? (ay > ax ? kAlongX : kAlongY) : 0, as masks: SSE2 has no blend, and the selects
    // took more instructions than the rest of the loop.
    const int16_t along = static_cast<int16_t>(kAlongY - (ay > ax));  // kAlongX when ay > ax
    const int16_t alive = static_cast<int16_t>(-(m >= low));          // all bits set when m >= low
    dir[x] = static_cast<uint8_t>(along & alive);
  }
  static_assert(kAlongY - 1 == kAlongX, "the direction's arithmetic above");
  for (const int x : {0, cols - 1}) {
    const int l = std::max(x - 1, 0), r = std::min(x + 1, cols - 1);
    const int16_t gx = static_cast<int16_t>((up[r] - up[l]) + 2 * (mid[r] - mid[l]) + (down[r] - down[l]));
    const int16_t gy = static_cast<int16_t>((down[l] - up[l]) + 2 * (down[x] - up[x]) + (down[r] - up[r]));
    dx[x] = gx;
    dy[x] = gy;
    mag[x] = static_cast<int16_t>(std::abs(gx) + std::abs(gy));
    dir[x] = 0;
  }
}

}  // namespace

void SobelMagnitude(const cv::Mat& image, int low, cv::Mat* gx, cv::Mat* gy, cv::Mat* magnitude,
                    cv::Mat* direction) {
  CHECK_EQ(image.type(), CV_8UC1);
  CHECK(image.isContinuous());
  CHECK(image.rows >= 3 && image.cols >= 3) << "image of " << image.cols << " x " << image.rows;
  const int rows = image.rows, cols = image.cols;
  gx->create(rows, cols, CV_16S);
  gy->create(rows, cols, CV_16S);
  magnitude->create(rows, cols, CV_16S);
  direction->create(rows, cols, CV_8U);
  const int16_t inner_low = static_cast<int16_t>(std::clamp(low, 0, static_cast<int>(INT16_MAX)));
  for (int y = 0; y < rows; ++y) {
    SobelRow(image.ptr<uint8_t>(std::max(y - 1, 0)), image.ptr<uint8_t>(y),
             image.ptr<uint8_t>(std::min(y + 1, rows - 1)), cols,
             y == 0 || y == rows - 1 ? INT16_MAX : inner_low, gx->ptr<int16_t>(y), gy->ptr<int16_t>(y),
             magnitude->ptr<int16_t>(y), direction->ptr<uint8_t>(y));
  }
}

}  // namespace sfm

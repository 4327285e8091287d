// The fast path's gradient pass (docs/segments.md, fast path step 1): the 3 x 3 Sobel derivatives
// of an 8-bit image, their magnitude |gx| + |gy| and each pixel's edge direction, in one pass.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace sfm {

// Edge direction of a pixel whose magnitude reaches the low threshold; 0 otherwise.
constexpr uint8_t kAlongX = 1;  // the edge runs along x: the gradient is mostly along y (|gy| > |gx|)
constexpr uint8_t kAlongY = 2;  // the edge runs along y

// gx, gy: CV_16S, exactly cv::spatialGradient(image, gx, gy, 3, cv::BORDER_REPLICATE) (gx = [-1 0 1]
// across x times [1 2 1] down y, gy its transpose; integer arithmetic). magnitude: CV_16S, |gx| +
// |gy|. direction: CV_8U, kAlongX or kAlongY where the magnitude reaches `low`, else 0; 0 on the
// border rows and columns, so that an edge walk never needs a bounds check. image: CV_8UC1,
// continuous, at least 3 x 3. The outputs are (re)allocated only if their size or type differs.
void SobelMagnitude(const cv::Mat& image, int low, cv::Mat* gx, cv::Mat* gy, cv::Mat* magnitude,
                    cv::Mat* direction);

}  // namespace sfm

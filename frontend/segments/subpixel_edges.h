// The reference path's edge filter: a Canny-type optimal edge detector (Gaussian-derivative
// gradient, non-maximum suppression, hysteresis) with sub-pixel localisation of each edge point
// along the gradient, following Devernay's quadratic interpolation of the gradient magnitude.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace sfm {

struct EdgePoint {
  float x = 0, y = 0;    // sub-pixel position, pixels
  float gx = 0, gy = 0;  // image gradient at the pixel (dark to bright), grey levels per pixel
};

// Edge points of an 8-bit single-channel image. `sigma` (pixels) is the scale of the Gaussian
// derivative; `low` <= `high` are the hysteresis thresholds on the gradient magnitude in grey
// levels per pixel. A point's sub-pixel offset is the vertex of the parabola through the
// magnitudes at the pixel and its two neighbours along the image axis closest to the gradient
// (Devernay 1995): unbiased for a symmetric edge profile, whatever the edge's angle.
std::vector<EdgePoint> DetectSubpixelEdges(const cv::Mat& grey, double sigma, double low, double high);

// Peak gradient magnitude, grey levels per pixel, of an ideal step of `contrast` grey levels seen
// through a Gaussian derivative of scale `sigma` pixels: contrast / (sqrt(2 pi) sigma).
double StepGradient(double contrast, double sigma);

}  // namespace sfm

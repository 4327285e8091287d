#include "frontend/segments/subpixel_edges.h"

#include <cmath>
#include <cstdint>

#include <glog/logging.h>
#include <opencv2/imgproc.hpp>

namespace sfm {
namespace {

// Sampled Gaussian G and derivative kernel D of scale sigma, radius ceil(3 sigma). D is scaled so
// that filtering a unit ramp gives 1 (gradients in grey levels per pixel); G sums to 1.
void GaussianKernels(double sigma, cv::Mat* smooth, cv::Mat* derivative) {
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  *smooth = cv::Mat(2 * radius + 1, 1, CV_32F);
  *derivative = cv::Mat(2 * radius + 1, 1, CV_32F);
  double sum = 0, moment = 0;
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-0.5 * i * i / (sigma * sigma));
    sum += g;
    moment += i * i * g;
  }
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-0.5 * i * i / (sigma * sigma));
    smooth->at<float>(i + radius) = static_cast<float>(g / sum);
    derivative->at<float>(i + radius) = static_cast<float>(i * g / moment);
  }
}

}  // namespace

double StepGradient(double contrast, double sigma) { return contrast / (std::sqrt(2 * M_PI) * sigma); }

std::vector<EdgePoint> DetectSubpixelEdges(const cv::Mat& grey, double sigma, double low, double high) {
  CHECK_EQ(grey.type(), CV_8UC1);
  CHECK_GT(sigma, 0);
  CHECK_LE(low, high);
  cv::Mat smooth, derivative, gx, gy;
  GaussianKernels(sigma, &smooth, &derivative);
  cv::sepFilter2D(grey, gx, CV_32F, derivative, smooth, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
  cv::sepFilter2D(grey, gy, CV_32F, smooth, derivative, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
  cv::Mat magnitude;
  cv::magnitude(gx, gy, magnitude);

  // Non-maximum suppression along the image axis closest to the gradient, with the sub-pixel
  // offset from the same three samples. Border pixels are left out: their neighbours are missing.
  const int rows = grey.rows, cols = grey.cols;
  cv::Mat offset(rows, cols, CV_32F, cv::Scalar(0));
  cv::Mat state(rows, cols, CV_8U, cv::Scalar(0));  // 0: not an edge, 1: candidate, 2: accepted
  std::vector<int> stack;
  for (int y = 1; y + 1 < rows; ++y) {
    const float* m = magnitude.ptr<float>(y);
    const float* up = magnitude.ptr<float>(y - 1);
    const float* down = magnitude.ptr<float>(y + 1);
    const float* dx = gx.ptr<float>(y);
    const float* dy = gy.ptr<float>(y);
    for (int x = 1; x + 1 < cols; ++x) {
      const float centre = m[x];
      if (centre < low) continue;
      const bool horizontal = std::abs(dx[x]) >= std::abs(dy[x]);
      const float before = horizontal ? m[x - 1] : up[x];
      const float after = horizontal ? m[x + 1] : down[x];
      // Strict on one side, loose on the other: a plateau of two equal pixels keeps exactly one.
      if (!(centre > before && centre >= after)) continue;
      offset.at<float>(y, x) = 0.5f * (before - after) / (before - 2 * centre + after);
      state.at<uint8_t>(y, x) = 1;
      if (centre >= high) {
        state.at<uint8_t>(y, x) = 2;
        stack.push_back(y * cols + x);
      }
    }
  }
  // Hysteresis: grow the strong edge points through 8-connected candidates.
  std::vector<int> accepted = stack;
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    const int y = index / cols, x = index % cols;
    for (int ny = y - 1; ny <= y + 1; ++ny) {
      for (int nx = x - 1; nx <= x + 1; ++nx) {
        uint8_t& s = state.at<uint8_t>(ny, nx);  // candidates are never on the border
        if (s != 1) continue;
        s = 2;
        stack.push_back(ny * cols + nx);
        accepted.push_back(ny * cols + nx);
      }
    }
  }

  std::vector<EdgePoint> points;
  points.reserve(accepted.size());
  for (const int index : accepted) {
    const int y = index / cols, x = index % cols;
    EdgePoint p;
    p.gx = gx.at<float>(y, x);
    p.gy = gy.at<float>(y, x);
    const float delta = offset.at<float>(y, x);
    const bool horizontal = std::abs(p.gx) >= std::abs(p.gy);
    p.x = static_cast<float>(x) + (horizontal ? delta : 0.f);
    p.y = static_cast<float>(y) + (horizontal ? 0.f : delta);
    points.push_back(p);
  }
  return points;
}

}  // namespace sfm

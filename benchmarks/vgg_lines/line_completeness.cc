#include "benchmarks/vgg_lines/line_completeness.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sfm_app/wireframe_evaluation.h"

namespace sfm {

LineCompleteness MeasureLineCompleteness(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& true_lines,
                                         const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<std::pair<int, int>>& edges, double threshold,
                                         double step) {
  LineCompleteness result;
  for (const auto& [a, b] : true_lines) {
    const double length = (b - a).norm();
    result.true_length += length;
    const int samples = std::max(2, static_cast<int>(std::ceil(length / step)) + 1);
    int within = 0;
    for (int s = 0; s < samples; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(s) / (samples - 1));
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& [i, j] : edges) nearest = std::min(nearest, DistanceToSegment(p, vertices[i], vertices[j]));
      within += nearest <= threshold;
    }
    result.within_length += length * within / samples;
  }
  return result;
}

namespace {

// Pixels from q to the 2D segment ab.
double DistanceToSegment2d(const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length_squared = ab.squaredNorm();
  const double u = length_squared > 0 ? std::clamp((q - a).dot(ab) / length_squared, 0.0, 1.0) : 0.0;
  return (a + u * ab - q).norm();
}

}  // namespace

LineImageSupport MeasureLineImageSupport(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& true_lines,
                                         const std::vector<LineSupportView>& views, double px, double step,
                                         int min_views) {
  LineImageSupport result;
  for (const auto& [a, b] : true_lines) {
    const double length = (b - a).norm();
    result.true_length += length;
    const int samples = std::max(2, static_cast<int>(std::ceil(length / step)) + 1);
    int visible = 0, detected = 0;
    for (int s = 0; s < samples; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(s) / (samples - 1));
      int seen_in = 0, detected_in = 0;
      for (const LineSupportView& view : views) {
        const Eigen::Vector3d x = view.K * (view.R * p + view.t);
        if (!(x.z() > 0)) continue;
        const Eigen::Vector2d pixel = x.head<2>() / x.z();
        if (pixel.x() < 0 || pixel.y() < 0 || pixel.x() > view.width || pixel.y() > view.height) continue;
        ++seen_in;
        for (const auto& [u, v] : view.segments) {
          if (DistanceToSegment2d(pixel, u, v) <= px) {
            ++detected_in;
            break;
          }
        }
      }
      visible += seen_in >= min_views;
      detected += detected_in >= min_views;
    }
    result.visible_length += length * visible / samples;
    result.detected_length += length * detected / samples;
  }
  return result;
}

}  // namespace sfm

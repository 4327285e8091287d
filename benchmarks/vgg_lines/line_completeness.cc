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

}  // namespace sfm

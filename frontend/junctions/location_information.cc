#include "frontend/junctions/location_information.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

namespace sfm {
namespace {

Eigen::Vector2d Normal(const Eigen::Vector2d& direction) { return {-direction.y(), direction.x()}; }

// The unit direction of a T's bar: its two segments from one detected line segment, or else the
// two pointing most nearly opposite ways (junction classification's reading of a T); zero when
// the directions are not finite.
Eigen::Vector2d BarDirection(const Junction& junction) {
  int bar_a = -1, bar_b = -1;
  double most_opposite = 2;
  for (int i = 0; i < junction.NumSegments(); ++i) {
    for (int j = i + 1; j < junction.NumSegments(); ++j) {
      const int line = junction.segments[i].line_segment;
      const double dot = line >= 0 && line == junction.segments[j].line_segment
                             ? -2
                             : junction.SegmentDirection(i).dot(junction.SegmentDirection(j));
      if (dot < most_opposite) {
        most_opposite = dot;
        bar_a = i;
        bar_b = j;
      }
    }
  }
  if (bar_a < 0) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d direction = junction.SegmentDirection(bar_a) - junction.SegmentDirection(bar_b);
  return direction.allFinite() && direction.norm() > 0 ? Eigen::Vector2d(direction.normalized())
                                                       : Eigen::Vector2d::Zero();
}

}  // namespace

Eigen::Matrix2d LocationSqrtInformation(const Junction& junction, double min_information) {
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  if (junction.type == JunctionType::kT) {
    const Eigen::Vector2d bar = BarDirection(junction);
    information = Normal(bar) * Normal(bar).transpose();
  } else if (junction.type != JunctionType::kX) {
    std::vector<int> lines_counted;
    for (int i = 0; i < junction.NumSegments(); ++i) {
      const int line = junction.segments[i].line_segment;
      if (line >= 0) {
        if (std::find(lines_counted.begin(), lines_counted.end(), line) != lines_counted.end()) continue;
        lines_counted.push_back(line);
      }
      const Eigen::Vector2d direction = junction.SegmentDirection(i);
      if (!direction.allFinite()) continue;
      information += Normal(direction) * Normal(direction).transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information);
  const Eigen::Vector2d root = solver.eigenvalues().cwiseMax(min_information).cwiseSqrt();
  return solver.eigenvectors() * root.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace sfm

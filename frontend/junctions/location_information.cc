#include "frontend/junctions/location_information.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

namespace sfm {

Eigen::Matrix2d LocationSqrtInformation(const Junction& junction, double min_information) {
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  std::vector<int> lines_counted;
  for (int i = 0; i < junction.NumSegments(); ++i) {
    const int line = junction.segments[i].line_segment;
    if (line >= 0) {
      if (std::find(lines_counted.begin(), lines_counted.end(), line) != lines_counted.end()) continue;
      lines_counted.push_back(line);
    }
    const Eigen::Vector2d direction = junction.SegmentDirection(i);
    if (!direction.allFinite()) continue;
    const Eigen::Vector2d normal(-direction.y(), direction.x());
    information += normal * normal.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information);
  const Eigen::Vector2d root = solver.eigenvalues().cwiseMax(min_information).cwiseSqrt();
  return solver.eigenvectors() * root.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace sfm

#include "frontend/matching/physical_constraints.h"

#include <cmath>

namespace sfm {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

bool KeepsCyclicOrder(const Eigen::Vector2d* directions, const Eigen::Vector2d* partner_directions,
                      int num_segments, int shift, double min_sin) {
  // With two segments the pair (2, 1) is the pair (1, 2) reversed: one test says it all.
  const int num_pairs = num_segments == 2 ? 1 : num_segments;
  for (int i = 0; i < num_pairs; ++i) {
    const int i_next = (i + 1) % num_segments;
    const int j = (i + shift) % num_segments;
    const int j_next = (i_next + shift) % num_segments;
    const double turn = Cross(directions[i], directions[i_next]);
    const double partner_turn = Cross(partner_directions[j], partner_directions[j_next]);
    if (std::abs(turn) < min_sin || std::abs(partner_turn) < min_sin) continue;
    if (turn * partner_turn <= 0) return false;
  }
  return true;
}

bool IsSmallRotation(const Eigen::Vector2d* directions, const Eigen::Vector2d* partner_directions,
                     int num_segments, int shift) {
  for (int i = 0; i < num_segments; ++i) {
    if (directions[i].dot(partner_directions[(i + shift) % num_segments]) <= 0) return false;
  }
  return true;
}

}  // namespace sfm

#include "frontend/junctions/classification.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace sfm {
namespace {

double Angle(const Junction& junction, const JunctionSegment& segment) {
  const Eigen::Vector2d d = segment.end - junction.location;
  return std::atan2(d.y(), d.x());
}

}  // namespace

void OrderClockwise(Junction* junction) {
  // Each angle computed once, not twice per comparison; std::sort sees the same comparisons as
  // when comparing atan2 results directly, so the order (ties included) is unchanged.
  std::vector<std::pair<double, JunctionSegment>> keyed;
  keyed.reserve(junction->segments.size());
  for (const JunctionSegment& segment : junction->segments) keyed.emplace_back(Angle(*junction, segment), segment);
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < keyed.size(); ++i) junction->segments[i] = keyed[i].second;
}

JunctionType ClassifyJunction(const Junction& junction, double collinear_tolerance_rad) {
  const int n = junction.NumSegments();
  if (n <= 2) return JunctionType::kL;
  if (n == 4) return JunctionType::kX;
  if (n > 4) return JunctionType::kN;

  // Three segments: the angles between clockwise neighbours, which sum to 360 degrees.
  double gaps[3];
  bool one_line = false;
  for (int i = 0; i < 3; ++i) {
    const JunctionSegment& a = junction.segments[i];
    const JunctionSegment& b = junction.segments[(i + 1) % 3];
    gaps[i] = std::remainder(Angle(junction, b) - Angle(junction, a), 2 * M_PI);
    if (gaps[i] < 0) gaps[i] += 2 * M_PI;
    // A T's bar gives two junction segments of one detected segment: collinear by construction.
    if (a.line_segment >= 0 && a.line_segment == b.line_segment) one_line = true;
  }
  for (double gap : gaps) {
    if (one_line || std::abs(gap - M_PI) <= collinear_tolerance_rad) return JunctionType::kT;
  }
  for (double gap : gaps) {
    if (gap > M_PI) return JunctionType::kArrow;
  }
  return JunctionType::kY;
}

}  // namespace sfm

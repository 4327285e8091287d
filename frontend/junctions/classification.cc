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

namespace {

// Most junctions have 2-4 segments: their sort keys live on the stack.
constexpr int kInlineSegments = 8;

// Sorts the segments clockwise and writes their angles, in the new order, to angles[0..n). Each
// angle is computed once, not twice per comparison; std::sort sees the same comparisons as when
// comparing atan2 results directly, so the order (ties included) is unchanged.
void SortClockwise(Junction* junction, double* angles) {
  const size_t n = junction->segments.size();
  std::pair<double, JunctionSegment> inline_keys[kInlineSegments];
  std::vector<std::pair<double, JunctionSegment>> heap_keys;
  std::pair<double, JunctionSegment>* keys = inline_keys;
  if (n > kInlineSegments) {
    heap_keys.resize(n);
    keys = heap_keys.data();
  }
  for (size_t i = 0; i < n; ++i) keys[i] = {Angle(*junction, junction->segments[i]), junction->segments[i]};
  std::sort(keys, keys + n, [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < n; ++i) {
    angles[i] = keys[i].first;
    junction->segments[i] = keys[i].second;
  }
}

// ClassifyJunction with the segments' angles given (angles[i] = Angle(junction, segments[i])).
JunctionType ClassifyWithAngles(const Junction& junction, const double* angles,
                                double collinear_tolerance_rad) {
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
    gaps[i] = std::remainder(angles[(i + 1) % 3] - angles[i], 2 * M_PI);
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

}  // namespace

void OrderClockwise(Junction* junction) {
  std::vector<double> angles(junction->segments.size());
  SortClockwise(junction, angles.data());
}

JunctionType ClassifyJunction(const Junction& junction, double collinear_tolerance_rad) {
  if (junction.NumSegments() != 3) return ClassifyWithAngles(junction, nullptr, collinear_tolerance_rad);
  double angles[3];
  for (int i = 0; i < 3; ++i) angles[i] = Angle(junction, junction.segments[i]);
  return ClassifyWithAngles(junction, angles, collinear_tolerance_rad);
}

JunctionType OrderClockwiseAndClassify(Junction* junction, double collinear_tolerance_rad) {
  double inline_angles[kInlineSegments];
  std::vector<double> heap_angles;
  double* angles = inline_angles;
  if (junction->segments.size() > kInlineSegments) {
    heap_angles.resize(junction->segments.size());
    angles = heap_angles.data();
  }
  SortClockwise(junction, angles);
  return ClassifyWithAngles(*junction, angles, collinear_tolerance_rad);
}

}  // namespace sfm

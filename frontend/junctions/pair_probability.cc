#include "frontend/junctions/pair_probability.h"

#include <algorithm>
#include <cmath>

namespace sfm {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Where p0 sits on one segment: inside it, or reached by moving one end-point by t.
struct SegmentContact {
  Contact contact;
  double t;  // eq. (8) change of the moved end-point; 0 inside
};

SegmentContact ContactAt(const SegmentLine& line, const Eigen::Vector2d& p0, double min_arm) {
  const double s = (p0 - line.p0).dot(line.n);  // position of p0 along the segment, from p0
  if (s >= min_arm && s <= line.length - min_arm) return {Contact::kThrough, 0.0};
  const EndChange change = NearEndChange(line, p0);
  return {change.near_end == 0 ? Contact::kEnd0 : Contact::kEnd1, change.t};
}

// Two nearly parallel segments as one line broken in two (see TestPair).
std::optional<PairHit> TestCollinear(const SegmentLine& a, const SegmentLine& b, int index_a, int index_b,
                                     const JunctionDetectorOptions& options) {
  // The facing ends are the closest pair of end-points.
  const Eigen::Vector2d ends_a[2] = {a.p0, a.p1};
  const Eigen::Vector2d ends_b[2] = {b.p0, b.p1};
  int near_a = 0, near_b = 0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if ((ends_a[i] - ends_b[j]).squaredNorm() < (ends_a[near_a] - ends_b[near_b]).squaredNorm()) {
        near_a = i;
        near_b = j;
      }
    }
  }
  const Eigen::Vector2d outward_a = near_a == 1 ? a.n : Eigen::Vector2d(-a.n);
  const Eigen::Vector2d outward_b = near_b == 1 ? b.n : Eigen::Vector2d(-b.n);
  if (outward_a.dot(outward_b) >= 0) return std::nullopt;  // side by side, not end to end
  const Eigen::Vector2d between = ends_b[near_b] - ends_a[near_a];
  if (std::abs(between.dot(a.q)) > options.collinear_max_offset_px ||
      std::abs(between.dot(b.q)) > options.collinear_max_offset_px) {
    return std::nullopt;
  }
  // Closing a gap g moves the two end-points by t_a + t_b = -g in total, and f(t_a) f(t_b) is the
  // same for every split of it; an overlap (g < 0) is two end-points running past each other.
  const double gap = between.dot(outward_a);
  if (std::abs(gap) > options.max_gap_px) return std::nullopt;
  const double probability = options.endpoint_model.F(-gap);
  if (probability < options.min_probability) return std::nullopt;
  PairHit hit;
  hit.segment_a = index_a;
  hit.segment_b = index_b;
  hit.contact_a = near_a == 0 ? Contact::kEnd0 : Contact::kEnd1;
  hit.contact_b = near_b == 0 ? Contact::kEnd0 : Contact::kEnd1;
  hit.probability = probability;
  return hit;
}

}  // namespace

EndChange NearEndChange(const SegmentLine& segment, const Eigen::Vector2d& p0) {
  const double s = (p0 - segment.p0).dot(segment.n);
  EndChange change;
  if (s < 0.5 * segment.length) {
    change.near_end = 0;
    change.t = s;  // outward is -n, so t = (p0_detected - p0).(-n)
  } else {
    change.near_end = 1;
    change.t = segment.length - s;  // outward is +n, so t = (p1_detected - p0).n
  }
  return change;
}

double PairProbability(const SegmentLine& a, const SegmentLine& b, const Eigen::Vector2d& p0,
                       const EndpointModel& model) {
  return model.F(NearEndChange(a, p0).t) * model.F(NearEndChange(b, p0).t);
}

std::optional<PairHit> TestPair(const std::vector<SegmentLine>& lines, int a, int b,
                                const JunctionDetectorOptions& options) {
  return TestPair(lines, a, b, options, CollinearMinSine(options));
}

double CollinearMinSine(const JunctionDetectorOptions& options) {
  return std::sin(options.collinear_tolerance_deg * kDegToRad);
}

std::optional<PairHit> TestPair(const std::vector<SegmentLine>& lines, int a, int b,
                                const JunctionDetectorOptions& options, double min_sine) {
  const SegmentLine& la = lines[a];
  const SegmentLine& lb = lines[b];
  const std::optional<Eigen::Vector2d> p0 = IntersectLinesMinSine(la, lb, min_sine);
  if (!p0) return TestCollinear(la, lb, a, b, options);

  const SegmentContact ca = ContactAt(la, *p0, options.min_arm_px);
  const SegmentContact cb = ContactAt(lb, *p0, options.min_arm_px);
  if (std::abs(ca.t) > options.max_gap_px || std::abs(cb.t) > options.max_gap_px) return std::nullopt;
  // f(0) = 1 for a segment whose interior holds p0: nothing of it moves.
  const double probability = options.endpoint_model.F(ca.t) * options.endpoint_model.F(cb.t);
  if (probability < options.min_probability) return std::nullopt;
  PairHit hit;
  hit.segment_a = a;
  hit.segment_b = b;
  hit.contact_a = ca.contact;
  hit.contact_b = cb.contact;
  hit.probability = probability;
  hit.location = *p0;
  return hit;
}

}  // namespace sfm

// The junction hypothesis for a pair of detected segments and its probability (paper section 2.2,
// with the end-point model of eq. 5 and the sign convention of eq. 8).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "frontend/junctions/intersection.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/segments/endpoint_model.h"

namespace sfm {

// The change of a segment's near end-point needed to reach a junction location p0.
struct EndChange {
  int near_end = 0;  // 0: p0 of the segment, 1: p1
  double t = 0;      // eq. (8): (detected near end - p0) . outward, outward = far end -> near end;
                     // t > 0: the segment runs past p0, t < 0: it stops short of p0. Pixels.
};

// The near end-point of `segment` (the one closer to p0 along the line) and its t.
EndChange NearEndChange(const SegmentLine& segment, const Eigen::Vector2d& p0);

// Section 2.2: the junction probability of two segments meeting at p0, the product over both of
// f(t) (eq. 5) for the change of the near end-point needed to reach p0.
double PairProbability(const SegmentLine& a, const SegmentLine& b, const Eigen::Vector2d& p0,
                       const EndpointModel& model);

// Which part of a segment a junction uses.
enum class Contact { kEnd0, kEnd1, kThrough };  // end-point p0, end-point p1, or its interior

// A pair of segments that passes the junction test.
struct PairHit {
  int segment_a = -1, segment_b = -1;
  Contact contact_a = Contact::kEnd0, contact_b = Contact::kEnd0;
  double probability = 0;  // product of f over the end-points moved (1 for none moved)
  // Eq. (6) point of the two lines; absent for two collinear pieces continuing one another, whose
  // meeting point the lines do not fix.
  std::optional<Eigen::Vector2d> location;
};

// Tests whether segments a and b (indices into `lines`) meet at one junction:
// - lines at least options.collinear_tolerance_deg from parallel meet at their eq. (6) point p0.
//   A segment whose interior holds p0 (at least options.min_arm_px from both ends) keeps its
//   end-points (the bar of a T, f = 1); otherwise its near end-point moves to p0 and contributes
//   f(t). So an end-point on another segment's interior is a T contact, never an L.
// - nearly parallel lines pass only as one line broken in two: near end-points facing each other,
//   each within options.collinear_max_offset_px of the other's line, and f of the gap closed.
// Returns the hit when its probability reaches options.min_probability and no end-point moves more
// than options.max_gap_px.
std::optional<PairHit> TestPair(const std::vector<SegmentLine>& lines, int a, int b,
                                const JunctionDetectorOptions& options);

// sin(options.collinear_tolerance_deg), the parallel limit of TestPair's line intersection.
double CollinearMinSine(const JunctionDetectorOptions& options);
// TestPair with CollinearMinSine(options) given: computed once for all the pairs of an image.
std::optional<PairHit> TestPair(const std::vector<SegmentLine>& lines, int a, int b,
                                const JunctionDetectorOptions& options, double min_sine);

}  // namespace sfm

// Line segment detection (paper section 2): the one entry point of the module.
//
// Two methods share the output convention:
//  - kReference follows the paper: an optimal (Canny-type, Gaussian-derivative) edge filter with
//    sub-pixel edge localisation, a Hough-transform line finder, a least-squares fit of each line to
//    its edge points, end-points the projections of the last edge points, lines split at gaps.
//  - kFast: one Sobel pass, anchored edge chaining (as in EDLines), chains split into straight
//    pieces by incremental least squares, an a-contrario (NFA) check of each piece.
// See docs/segments.md for how each default below was chosen and how well each method does.
//
// Output convention: pixel coordinates with the origin at the centre of the top-left pixel, x right,
// y down (as OpenCV). Each segment is oriented so that the brighter side lies along its Normal():
// the mean image gradient (dark to bright) has a positive component along Normal().
#pragma once

#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"
#include "util/status.h"

namespace sfm {

enum class SegmentMethod { kReference, kFast };

// Options of the reference path (Canny-type edge filter + Hough transform).
struct ReferenceSegmentOptions {
  double edge_sigma = 1.0;            // pixels: scale of the Gaussian-derivative edge filter
  double hough_angle_step_deg = 0.5;  // degrees: accumulator resolution in the line normal's angle
  double hough_rho_step = 1.0;        // pixels: accumulator resolution in the line's distance rho
  double vote_window_deg = 5.0;       // degrees: each edge point votes for normals this close to its gradient
  int min_votes = 5;                  // accumulator peaks below this many votes end the search
  double gather_distance = 2.0;       // pixels: edge points this close to a Hough peak's line are fitted
  double fit_distance = 1.0;          // pixels: edge points this close to the fitted line support it
  double angle_tolerance_deg = 30.0;  // degrees: largest angle between an edge point's gradient and the line normal
};

// Options of the fast path (Sobel + anchored chaining + incremental splitting).
struct FastSegmentOptions {
  double presmooth_sigma = 0.7;     // pixels: Gaussian pre-smoothing before the Sobel pass (0: none)
  double line_tolerance = 1.0;      // pixels: a chain pixel farther than this from the growing line ends it
  double log10_nfa_max = 0.0;       // a piece is kept if log10(number of false alarms) <= this (NFA <= 1)
  // A piece shorter than min_length whose end meets the end of a piece at least min_length long
  // (of any chain) at a corner is measured from that corner, as a short side between two corners
  // (docs/segments.md, step 7). false: only short sides within one chain, between two corners.
  // Off by default: it raises junction recall by one point (82.5 -> 83.5 %) but its extra short
  // junctions on real images cost VGG matching precision on held-out odometry seeds (99.0 / 98.4 ->
  // 96.6 / 96.2 %, under the 97 % goal) and Strecha's refined shape (docs/junction_results.md).
  bool corners_between_chains = false;
  // At an end-point of a segment with no other segment's end-point within 2 max_gap, look for the
  // corner's missing side in the gradient field: a ray of aligned gradient orientation, tested
  // a-contrario, refitted to the sub-pixel edge points across it (branch_segments.h;
  // docs/segments.md, step 8). On by default (session 4): junction recall on generated vertices
  // 82.5 -> 84.3 % (held-out sequences 80.1 -> 81.3 %), precision 91.6 -> 91.9 %, VGG matching
  // precision 98.1-98.8 % on odometry seeds 1-3, segments + junctions 2.49 -> 2.86-2.89 x Canny
  // on VGG (docs/junction_results.md, "Session 4").
  bool branches_at_free_ends = true;
  // With branches_at_free_ends: at a free end of a segment B, continue the line of a segment A
  // that stops 3-12 px short of their corner at a corner of its own, when the gradient along the
  // gap is aligned with A's line (a-contrario, branch_segments.h; docs/segments.md, step 8).
  // With branches_to_far_corners, on by default (session 5): junction recall on generated vertices
  // 84.3 -> 85.3 % (held-out sequences 81.3 -> 82.6 %), precision 91.9 -> 92.2 %, VGG matching
  // precision 97.8-98.7 % on odometry seeds 1-3 (docs/junction_results.md, "Session 5").
  bool bridges_past_corners = true;
  // With branches_at_free_ends: a branch whose far end stops at another segment's corner (an L or a
  // T within max_gap) is measured from corner to corner for min_length, as the short sides of step 7.
  bool branches_to_far_corners = true;
  // A piece shorter than min_length (down to min_contact_length) whose line meets a segment at
  // least min_length long within max_gap of one of its end-points (an L with that segment's end,
  // or a T on its interior) is kept if its NFA against the family of such pieces (their count per
  // image) is at most 10^log10_nfa_max; the chain points no regular piece holds are split again
  // with 4-point seed windows to find them; every sample must reach the high edge threshold
  // (docs/segments.md, step 7). Off by default (session 6, docs/junction_results.md): junction
  // recall on generated vertices 86.4 -> 89.3 % (held-out 86.5 -> 88.3 %) at unchanged precision,
  // but VGG matching precision 98.2 -> 96.6 %, generated matching recall 91.2 -> 89.0 % and about
  // 19 % more instructions for segments + junctions on VGG (session 6, part 2).
  bool short_pieces_at_contacts = false;
  double min_contact_length = 4.0;  // pixels: shortest piece short_pieces_at_contacts keeps
};

struct SegmentDetectorOptions {
  SegmentMethod method = SegmentMethod::kFast;
  // Edge contrast thresholds, in grey levels of an ideal step edge, for both methods: a pixel may
  // continue an edge above `low`, and an edge may start only at a pixel above `high` (hysteresis
  // in the reference path, anchors in the fast path).
  double edge_contrast_low = 5.0;    // grey levels
  double edge_contrast_high = 10.0;  // grey levels
  // pixels: shorter segments are dropped. The shortest length at which pure noise of twice a
  // camera's noise (sigma 4 grey levels) gives at most one false segment per 640 x 480 image on
  // average (measured for the fast path: 0.86 at 9 px, 2.0 at 8 px; docs/segments.md).
  double min_length = 9.0;
  double max_gap = 3.0;              // pixels: a longer run without edge points splits a line (>= 1.5)
  // pixels: a segment whose two end-points both lie this close to the same image border is dropped.
  // The border is not a scene edge, but the filters' padding and sensor artefacts (a dark first or
  // last column) make one there; 2 px is the reach of the edge filter's support at sigma 1 (0:
  // keep everything).
  double border_margin = 2.0;
  ReferenceSegmentOptions reference;
  FastSegmentOptions fast;

  // OK, or a message naming the first bad field.
  Status Check() const;
};

// The line segments of an 8-bit single-channel image. `options` must pass Check().
LineSegments DetectLineSegments(const cv::Mat& grey, const SegmentDetectorOptions& options);

// Removes the segments whose two end-points both lie within `margin` pixels of the same border of
// an image of `size` (pixel centres at integer coordinates, 0 .. width-1).
void DropBorderSegments(const cv::Size& size, double margin, LineSegments* segments);

}  // namespace sfm

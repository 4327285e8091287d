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

#include <string>

#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"
#include "util/status.h"

namespace sfm {

enum class SegmentMethod { kReference, kFast };

// "reference" or "fast".
const char* ToString(SegmentMethod method);
// The method named `name` (as ToString writes it), or an error naming the choices.
Status FromString(const std::string& name, SegmentMethod* method);

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

// Options of the fast path (Sobel + anchored chaining + incremental splitting). Its short sides
// between corners and its branches at free ends are steps 7 and 8 of docs/segments.md.
struct FastSegmentOptions {
  double presmooth_sigma = 0.7;  // pixels: Gaussian pre-smoothing before the Sobel pass (0: none)
  double line_tolerance = 1.0;   // pixels: a chain pixel farther than this from the growing line ends it
  double log10_nfa_max = 0.0;    // a piece is kept if log10(number of false alarms) <= this (NFA <= 1)
};

struct SegmentDetectorOptions {
  SegmentMethod method = SegmentMethod::kFast;
  // Edge contrast thresholds, in grey levels of an ideal step edge, for both methods: a pixel may
  // continue an edge above `low`, and an edge may start only at a pixel above `high` (hysteresis
  // in the reference path, anchors in the fast path).
  double edge_contrast_low = 5.0;    // grey levels
  double edge_contrast_high = 10.0;  // grey levels
  // pixels: shorter segments are dropped; the shortest length at which noise of sigma 4 grey levels
  // gives at most one false segment per 640 x 480 image (docs/segments.md, "Defaults").
  double min_length = 9.0;
  double max_gap = 3.0;              // pixels: a longer run without edge points splits a line (>= 1.5)
  // pixels: a segment whose two end-points both lie this close to the same image border is dropped
  // (padding and sensor artefacts make edges there); the edge filter's reach at sigma 1 (0: keep all).
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

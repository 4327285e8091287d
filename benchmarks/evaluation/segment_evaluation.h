// Quality of detected line segments against ground-truth segments (used by the benchmark app and
// the tests): how much of each true segment is found, and how far off the end-points are.
#pragma once

#include <string>
#include <vector>

#include "frontend/segments/line_segment.h"
#include "util/status.h"

namespace sfm {

struct SegmentEvaluationOptions {
  double max_distance = 1.5;       // pixels: detected points farther from the true line cover nothing
  double max_angle_deg = 5.0;      // degrees: detected segments at a larger angle cover nothing
  double min_coverage = 0.8;       // share of a true segment's length the detections must cover
  double min_match_overlap = 0.5;  // share of its length one detection must cover to be its match
  double min_true_length = 20.0;   // pixels: shorter true segments are left out (VGG's has none)

  Status Check() const;
};

// One true segment's result.
struct TrueSegmentResult {
  double coverage = 0;  // share of its length covered by the union of compatible detections
  int match = -1;       // index of the detection covering most of it, if >= min_match_overlap; else -1
  // For a match, per true end-point (p0, p1): the distance to the matched detection's end-point on
  // that side (pixels) and the signed offset along the line, detected minus true with the outward
  // direction positive (eq. 8: t > 0 when the detection is too long).
  double endpoint_error[2] = {0, 0};
  double endpoint_t[2] = {0, 0};
};

struct SegmentEvaluation {
  int num_true = 0;     // true segments evaluated (at least min_true_length long)
  int num_detected = 0;
  int num_covered = 0;  // true segments with coverage >= min_coverage
  int num_matched = 0;  // true segments with a match
  std::vector<double> endpoint_errors;  // pixels, two per matched true segment
  std::vector<double> endpoint_t;       // pixels, two per matched true segment (eq. 8 sign)
  std::vector<double> line_distances;   // pixels: mean distance of each match's end-points to the true line

  double CoveredShare() const { return num_true ? static_cast<double>(num_covered) / num_true : 0; }
  double MatchedShare() const { return num_true ? static_cast<double>(num_matched) / num_true : 0; }
  // Pools another image's results into this one.
  void Add(const SegmentEvaluation& other);
};

// Per true segment results of `detected` against `truth`.
std::vector<TrueSegmentResult> EvaluateEachSegment(const LineSegments& detected, const LineSegments& truth,
                                                   const SegmentEvaluationOptions& options);

// The pooled evaluation of `detected` against `truth` (one image).
SegmentEvaluation EvaluateSegments(const LineSegments& detected, const LineSegments& truth,
                                   const SegmentEvaluationOptions& options);

// The q-quantile (0..1) of values, by linear interpolation; 0 for an empty vector.
double Quantile(std::vector<double> values, double q);

// Reads a VGG ".lines" file: one segment per line, "x0 y0 x1 y1" (any whitespace).
Status ReadVggLines(const std::string& path, LineSegments* segments);

// Reads the visible wireframe segments of a generated sequence's frame (truth/frames/NNNNNN.txt,
// docs/generator.md): the "segment" records, with their end-points in the stored (distorted)
// image. With lens distortion the true edge is a curve and the segment its chord.
Status ReadGeneratorSegments(const std::string& path, LineSegments* segments);

}  // namespace sfm

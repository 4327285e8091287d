#include "benchmarks/evaluation/segment_evaluation.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <utility>

namespace sfm {
namespace {

// The interval, in positions along `truth` (0 at truth.p0), covered by the part of `d` that lies
// within max_distance of the true line; false when no part of it does.
bool CoveredInterval(const LineSegment& d, const LineSegment& truth, double max_distance, double* from,
                     double* to) {
  const Eigen::Vector2d n = truth.Direction();
  const Eigen::Vector2d q = truth.Normal();
  const double d0 = q.dot(d.p0 - truth.p0), d1 = q.dot(d.p1 - truth.p0);
  // The distance is linear along d: keep u in [0, 1] with |d0 + u (d1 - d0)| <= max_distance.
  double u0 = 0, u1 = 1;
  const double slope = d1 - d0;
  if (std::abs(slope) < 1e-12) {
    if (std::abs(d0) > max_distance) return false;
  } else {
    double a = (-max_distance - d0) / slope, b = (max_distance - d0) / slope;
    if (a > b) std::swap(a, b);
    u0 = std::max(u0, a);
    u1 = std::min(u1, b);
    if (u0 > u1) return false;
  }
  const double s0 = n.dot(d.p0 - truth.p0), s1 = n.dot(d.p1 - truth.p0);
  *from = s0 + u0 * (s1 - s0);
  *to = s0 + u1 * (s1 - s0);
  if (*from > *to) std::swap(*from, *to);
  return true;
}

}  // namespace

Status SegmentEvaluationOptions::Check() const {
  if (!(max_distance > 0)) return Status::Error("SegmentEvaluationOptions.max_distance must be > 0");
  if (!(max_angle_deg > 0 && max_angle_deg < 90)) {
    return Status::Error("SegmentEvaluationOptions.max_angle_deg must be in (0, 90)");
  }
  if (!(min_coverage > 0 && min_coverage <= 1)) {
    return Status::Error("SegmentEvaluationOptions.min_coverage must be in (0, 1]");
  }
  if (!(min_match_overlap > 0 && min_match_overlap <= 1)) {
    return Status::Error("SegmentEvaluationOptions.min_match_overlap must be in (0, 1]");
  }
  if (!(min_true_length >= 0)) return Status::Error("SegmentEvaluationOptions.min_true_length must be >= 0");
  return Status::Ok();
}

void SegmentEvaluation::Add(const SegmentEvaluation& other) {
  num_true += other.num_true;
  num_detected += other.num_detected;
  num_covered += other.num_covered;
  num_matched += other.num_matched;
  endpoint_errors.insert(endpoint_errors.end(), other.endpoint_errors.begin(), other.endpoint_errors.end());
  endpoint_t.insert(endpoint_t.end(), other.endpoint_t.begin(), other.endpoint_t.end());
  line_distances.insert(line_distances.end(), other.line_distances.begin(), other.line_distances.end());
}

std::vector<TrueSegmentResult> EvaluateEachSegment(const LineSegments& detected, const LineSegments& truth,
                                                   const SegmentEvaluationOptions& options) {
  const double min_cos = std::cos(options.max_angle_deg * M_PI / 180);
  std::vector<TrueSegmentResult> results(truth.size());
  std::vector<std::pair<double, double>> intervals;
  for (size_t t = 0; t < truth.size(); ++t) {
    const LineSegment& g = truth[t];
    const double length = g.Length();
    if (length <= 0 || length < options.min_true_length) continue;
    const Eigen::Vector2d n = g.Direction();
    intervals.clear();
    double best_overlap = 0;
    int best = -1;
    for (size_t i = 0; i < detected.size(); ++i) {
      const LineSegment& d = detected[i];
      if (d.Length() <= 0 || std::abs(d.Direction().dot(n)) < min_cos) continue;
      double from = 0, to = 0;
      if (!CoveredInterval(d, g, options.max_distance, &from, &to)) continue;
      from = std::max(from, 0.0);
      to = std::min(to, length);
      if (to <= from) continue;
      intervals.emplace_back(from, to);
      if (to - from > best_overlap) {
        best_overlap = to - from;
        best = static_cast<int>(i);
      }
    }
    std::sort(intervals.begin(), intervals.end());
    double covered = 0, reach = 0;
    for (const auto& [from, to] : intervals) {
      const double start = std::max(from, reach);
      if (to > start) covered += to - start;
      reach = std::max(reach, to);
    }
    TrueSegmentResult& result = results[t];
    result.coverage = covered / length;
    if (best < 0 || best_overlap < options.min_match_overlap * length) continue;
    result.match = best;
    // Pair the detection's end-points with the true ones by their order along the true segment.
    const LineSegment& d = detected[best];
    const bool same_order = n.dot(d.p1 - d.p0) >= 0;
    const Eigen::Vector2d near0 = same_order ? d.p0 : d.p1;
    const Eigen::Vector2d near1 = same_order ? d.p1 : d.p0;
    result.endpoint_error[0] = (near0 - g.p0).norm();
    result.endpoint_error[1] = (near1 - g.p1).norm();
    result.endpoint_t[0] = -n.dot(near0 - g.p0);  // outward at p0 is -n
    result.endpoint_t[1] = n.dot(near1 - g.p1);
  }
  return results;
}

SegmentEvaluation EvaluateSegments(const LineSegments& detected, const LineSegments& truth,
                                   const SegmentEvaluationOptions& options) {
  SegmentEvaluation evaluation;
  evaluation.num_detected = static_cast<int>(detected.size());
  const std::vector<TrueSegmentResult> results = EvaluateEachSegment(detected, truth, options);
  for (size_t t = 0; t < truth.size(); ++t) {
    if (truth[t].Length() < options.min_true_length) continue;
    ++evaluation.num_true;
    const TrueSegmentResult& r = results[t];
    if (r.coverage >= options.min_coverage) ++evaluation.num_covered;
    if (r.match < 0) continue;
    ++evaluation.num_matched;
    const LineSegment& d = detected[r.match];
    const Eigen::Vector2d q = truth[t].Normal();
    for (int e = 0; e < 2; ++e) {
      evaluation.endpoint_errors.push_back(r.endpoint_error[e]);
      evaluation.endpoint_t.push_back(r.endpoint_t[e]);
    }
    evaluation.line_distances.push_back(
        0.5 * (std::abs(q.dot(d.p0 - truth[t].p0)) + std::abs(q.dot(d.p1 - truth[t].p0))));
  }
  return evaluation;
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double position = std::clamp(q, 0.0, 1.0) * (values.size() - 1);
  const size_t below = static_cast<size_t>(position);
  const size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - below) * (values[above] - values[below]);
}

Status ReadVggLines(const std::string& path, LineSegments* segments) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  segments->clear();
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(text);
    LineSegment s;
    if (!(fields >> s.p0.x() >> s.p0.y() >> s.p1.x() >> s.p1.y())) {
      return Status::Error(path + ":" + std::to_string(line) + ": expected 4 numbers \"x0 y0 x1 y1\"");
    }
    segments->push_back(s);
  }
  return Status::Ok();
}

Status ReadGeneratorSegments(const std::string& path, LineSegments* segments) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  segments->clear();
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (text.rfind("segment ", 0) != 0) continue;
    // segment <edge> <t0> <t1> <u0> <v0> <u1> <v1> <u0_dist> <v0_dist> <u1_dist> <v1_dist> <end0> <end1>
    std::istringstream fields(text.substr(8));
    double skip = 0;
    LineSegment s;
    std::string end0, end1;
    if (!(fields >> skip >> skip >> skip >> skip >> skip >> skip >> skip >> s.p0.x() >> s.p0.y() >> s.p1.x() >>
          s.p1.y() >> end0 >> end1)) {
      return Status::Error(path + ":" + std::to_string(line) + ": expected a segment record of 13 fields");
    }
    segments->push_back(s);
  }
  return Status::Ok();
}

}  // namespace sfm

#include "benchmarks/evaluation/junction_evaluation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "frontend/junctions/classification.h"

namespace sfm {
namespace {

// A visible edge part leaving a vertex: the pixel of its other end and its visible length.
struct Arm {
  Eigen::Vector2d far = Eigen::Vector2d::Zero();
  double length = 0;
  int segment = -1;  // index into FrameTruth::segments
};

// The part of from -> to that stays in [-0.5, width - 0.5] x [-0.5, height - 0.5] from `from` on
// (`from` inside): its far end. Unchanged when width or height is not positive.
Eigen::Vector2d ClipToImage(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int width, int height) {
  if (width <= 0 || height <= 0) return to;
  const Eigen::Vector2d d = to - from;
  double u = 1;  // fraction of from -> to inside (Liang-Barsky, one side only: `from` is inside)
  const double low[2] = {-0.5, -0.5}, high[2] = {width - 0.5, height - 0.5};
  for (int a = 0; a < 2; ++a) {
    if (d[a] > 0 && from[a] + u * d[a] > high[a]) u = (high[a] - from[a]) / d[a];
    if (d[a] < 0 && from[a] + u * d[a] < low[a]) u = (low[a] - from[a]) / d[a];
  }
  return from + std::max(0.0, u) * d;
}

// The length that min_edge_px is compared with: undistorted, or in the stored image (the chord).
double EdgeLength(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const TrueJunctionOptions& options) {
  if (options.stored_camera == nullptr) return (b - a).norm();
  return (options.stored_camera->DistortPixel(b) - options.stored_camera->DistortPixel(a)).norm();
}

// For every vertex of the frame, the visible edge parts that start at it (clipped to the image
// when the options give its size).
std::map<int, std::vector<Arm>> ArmsOfVertices(const Wireframe& wireframe, const FrameTruth& frame,
                                               const TrueJunctionOptions& options) {
  std::map<int, std::vector<Arm>> arms;
  auto arm = [&](const Eigen::Vector2d& at, const Eigen::Vector2d& far, int index) {
    const Eigen::Vector2d end = ClipToImage(at, far, options.image_width, options.image_height);
    return Arm{end, EdgeLength(at, end, options), index};
  };
  for (size_t i = 0; i < frame.segments.size(); ++i) {
    const VisibleSegment& s = frame.segments[i];
    const WireEdge& edge = wireframe.edges.at(s.edge);
    const int index = static_cast<int>(i);
    // end[0] is at t[0]; it is the edge's own end (vertex_a) only when marked kVertex.
    if (s.end[0] == SegmentEnd::kVertex) arms[edge.vertex_a].push_back(arm(s.pixel[0], s.pixel[1], index));
    if (s.end[1] == SegmentEnd::kVertex) arms[edge.vertex_b].push_back(arm(s.pixel[1], s.pixel[0], index));
  }
  return arms;
}

// True when the arms are two collinear ones: a straight edge through the vertex, no junction.
bool TwoCollinear(const Eigen::Vector2d& at, const std::vector<Arm>& arms, double tolerance) {
  if (arms.size() != 2) return false;
  const Eigen::Vector2d a = (arms[0].far - at).normalized(), b = (arms[1].far - at).normalized();
  return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) >= M_PI - tolerance;
}

JunctionType TypeOf(const Eigen::Vector2d& at, const std::vector<Arm>& arms, double tolerance) {
  Junction junction;
  junction.location = at;
  for (const Arm& arm : arms) junction.segments.push_back({arm.far, -1});
  OrderClockwise(&junction);
  return ClassifyJunction(junction, tolerance);
}

double DistanceToSegment(const Eigen::Vector2d& p, const LineSegment& s) {
  const Eigen::Vector2d d = s.p1 - s.p0;
  const double length2 = d.squaredNorm();
  const double u = length2 > 0 ? std::clamp((p - s.p0).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (s.p0 + u * d - p).norm();
}

// Intersection of the lines of two segments; false when they are parallel.
bool IntersectSegmentLines(const LineSegment& a, const LineSegment& b, Eigen::Vector2d* p) {
  const Eigen::Vector2d da = a.p1 - a.p0, db = b.p1 - b.p0;
  const double denominator = da.x() * db.y() - da.y() * db.x();
  if (std::abs(denominator) < 1e-12) return false;
  const Eigen::Vector2d w = b.p0 - a.p0;
  const double u = (w.x() * db.y() - w.y() * db.x()) / denominator;
  *p = a.p0 + u * da;
  return true;
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Bilinear interpolation of an 8-bit image; false outside it.
bool Bilinear(const cv::Mat& image, const Eigen::Vector2d& p, double* value) {
  const double x = p.x(), y = p.y();
  if (!(x >= 0 && y >= 0 && x <= image.cols - 1 && y <= image.rows - 1)) return false;
  const int x0 = std::min(static_cast<int>(x), image.cols - 2), y0 = std::min(static_cast<int>(y), image.rows - 2);
  const double ax = x - x0, ay = y - y0;
  const uchar* r0 = image.ptr<uchar>(y0);
  const uchar* r1 = image.ptr<uchar>(y0 + 1);
  *value = (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) + ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
  return true;
}

}  // namespace

std::vector<double> EdgeContrasts(const cv::Mat& image, const FrameTruth& frame, const EdgeContrastOptions& options) {
  if (image.type() != CV_8UC1) return std::vector<double>(frame.segments.size(), -1.0);
  std::vector<double> contrasts;
  contrasts.reserve(frame.segments.size());
  for (const VisibleSegment& s : frame.segments) {
    const Eigen::Vector2d d = s.pixel[1] - s.pixel[0];
    const double length = d.norm();
    double sum = 0;
    int samples = 0;
    if (length > 2 * options.end_margin_px) {
      const Eigen::Vector2d u = d / length, n(-u.y(), u.x());
      for (double a = options.end_margin_px; a <= length - options.end_margin_px + 1e-9; a += 1.0) {
        const Eigen::Vector2d p = s.pixel[0] + a * u;
        double plus = 0, minus = 0;
        if (!Bilinear(image, p + options.offset_px * n, &plus) || !Bilinear(image, p - options.offset_px * n, &minus)) {
          continue;
        }
        sum += std::abs(plus - minus);
        ++samples;
      }
    }
    contrasts.push_back(samples > 0 ? sum / samples : -1.0);
  }
  return contrasts;
}

FrameTrueJunctions TrueJunctionsOfFrame(const Wireframe& wireframe, const FrameTruth& frame,
                                        const TrueJunctionOptions& options) {
  const std::map<int, std::vector<Arm>> arms_of = ArmsOfVertices(wireframe, frame, options);
  FrameTrueJunctions result;
  for (const VisibleVertex& v : frame.vertices) {
    const auto it = arms_of.find(v.vertex);
    if (it == arms_of.end()) continue;
    const std::vector<Arm>& arms = it->second;
    if (arms.size() < 2 || TwoCollinear(v.pixel, arms, options.collinear_tolerance_rad)) continue;
    std::vector<Arm> long_arms;
    for (const Arm& arm : arms) {
      if (arm.length >= options.min_edge_px) long_arms.push_back(arm);
    }
    TrueVertexJunction junction;
    junction.vertex = v.vertex;
    junction.location = v.pixel;
    junction.num_edges = static_cast<int>(arms.size());
    junction.num_long_edges = static_cast<int>(long_arms.size());
    junction.detectable =
        long_arms.size() >= 2 && !TwoCollinear(v.pixel, long_arms, options.collinear_tolerance_rad);
    junction.contrast_detectable = junction.detectable;
    if (options.segment_contrast != nullptr && junction.detectable) {
      std::vector<Arm> seen_arms;
      for (const Arm& arm : long_arms) {
        if (options.segment_contrast->at(arm.segment) >= options.min_contrast) seen_arms.push_back(arm);
      }
      junction.contrast_detectable =
          seen_arms.size() >= 2 && !TwoCollinear(v.pixel, seen_arms, options.collinear_tolerance_rad);
    }
    for (const Arm& arm : long_arms) junction.long_edge_ends.push_back(arm.far);
    junction.type = TypeOf(v.pixel, junction.detectable ? long_arms : arms, options.collinear_tolerance_rad);
    result.vertices.push_back(junction);
  }
  for (const VisibleSegment& s : frame.segments) {
    if (EdgeLength(s.pixel[0], s.pixel[1], options) < options.min_edge_px) continue;
    for (int e = 0; e < 2; ++e) {
      if (s.end[e] == SegmentEnd::kOcclusion) result.occlusions.push_back(s.pixel[e]);
    }
  }
  return result;
}

std::vector<TrueSegment> TrueSegmentsOfFrame(const Wireframe& wireframe, const FrameTruth& frame,
                                             const TrueJunctionOptions& options) {
  const std::map<int, std::vector<Arm>> arms_of = ArmsOfVertices(wireframe, frame, options);
  std::vector<TrueSegment> result;
  for (const VisibleSegment& s : frame.segments) {
    TrueSegment t;
    t.segment.p0 = s.pixel[0];
    t.segment.p1 = s.pixel[1];
    if (t.segment.Length() <= 0) continue;
    const WireEdge& edge = wireframe.edges.at(s.edge);
    for (int e = 0; e < 2; ++e) {
      t.end[e] = s.end[e];
      if (s.end[e] == SegmentEnd::kOcclusion) t.real_end[e] = true;
      if (s.end[e] != SegmentEnd::kVertex) continue;
      // The edge's own end: real unless another visible edge leaves the vertex straight on.
      const int vertex = e == 0 ? edge.vertex_a : edge.vertex_b;
      const Eigen::Vector2d at = s.pixel[e];
      const Eigen::Vector2d inward = (s.pixel[1 - e] - at).normalized();
      bool continued = false;
      const auto it = arms_of.find(vertex);
      if (it != arms_of.end()) {
        for (const Arm& arm : it->second) {
          const Eigen::Vector2d d = arm.far - at;
          if (d.norm() < 1e-9) continue;
          if (std::acos(std::clamp(d.normalized().dot(inward), -1.0, 1.0)) >= M_PI - options.collinear_tolerance_rad) {
            continued = true;
          }
        }
      }
      t.real_end[e] = !continued;
    }
    result.push_back(t);
  }
  return result;
}

std::vector<SegmentJunction> JunctionsFromSegments(const LineSegments& segments,
                                                   const SegmentJunctionOptions& options) {
  const double min_sin = std::sin(options.min_angle_deg * M_PI / 180);
  const double c = options.contact_px;
  struct PairPoint {
    Eigen::Vector2d p;
    int a, b;
  };
  std::vector<PairPoint> pairs;
  for (size_t i = 0; i < segments.size(); ++i) {
    const LineSegment& a = segments[i];
    if (!(a.Length() > 0)) continue;
    for (size_t j = i + 1; j < segments.size(); ++j) {
      const LineSegment& b = segments[j];
      if (!(b.Length() > 0)) continue;
      const double sine = std::abs(a.Direction().x() * b.Direction().y() - a.Direction().y() * b.Direction().x());
      if (sine < min_sin) continue;
      Eigen::Vector2d p;
      if (!IntersectSegmentLines(a, b, &p)) continue;
      const double end_a = std::min((a.p0 - p).norm(), (a.p1 - p).norm());
      const double end_b = std::min((b.p0 - p).norm(), (b.p1 - p).norm());
      const bool meet = (end_a <= c && DistanceToSegment(p, b) <= c) || (end_b <= c && DistanceToSegment(p, a) <= c);
      if (meet) pairs.push_back({p, static_cast<int>(i), static_cast<int>(j)});
    }
  }
  // Single-linkage clusters of the pair points.
  std::vector<int> parent(pairs.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (size_t j = i + 1; j < pairs.size(); ++j) {
      if ((pairs[i].p - pairs[j].p).norm() <= options.merge_px) parent[Find(parent, i)] = Find(parent, j);
    }
  }
  std::map<int, std::vector<int>> clusters;
  for (size_t i = 0; i < pairs.size(); ++i) clusters[Find(parent, i)].push_back(static_cast<int>(i));

  std::vector<SegmentJunction> result;
  for (const auto& [root, members] : clusters) {
    SegmentJunction junction;
    for (int m : members) {
      junction.location += pairs[m].p;
      junction.segments.push_back(pairs[m].a);
      junction.segments.push_back(pairs[m].b);
    }
    junction.location /= members.size();
    std::sort(junction.segments.begin(), junction.segments.end());
    junction.segments.erase(std::unique(junction.segments.begin(), junction.segments.end()), junction.segments.end());
    // Junction segments to the far ends; a segment split well inside gives two (a T's bar).
    Junction shape;
    shape.location = junction.location;
    for (int k : junction.segments) {
      const LineSegment& s = segments[k];
      const double along = s.Direction().dot(junction.location - s.p0);
      if (along > c && along < s.Length() - c) {
        shape.segments.push_back({s.p0, k});
        shape.segments.push_back({s.p1, k});
      } else {
        const bool p0_near = (s.p0 - junction.location).norm() < (s.p1 - junction.location).norm();
        shape.segments.push_back({p0_near ? s.p1 : s.p0, k});
      }
    }
    OrderClockwise(&shape);
    junction.type = ClassifyJunction(shape, options.min_angle_deg * M_PI / 180);
    result.push_back(junction);
  }
  return result;
}

std::vector<PointMatch> MatchPoints(const std::vector<Eigen::Vector2d>& truth,
                                    const std::vector<Eigen::Vector2d>& detected, double radius) {
  std::vector<PointMatch> candidates;
  for (size_t i = 0; i < truth.size(); ++i) {
    for (size_t j = 0; j < detected.size(); ++j) {
      const double d = (truth[i] - detected[j]).norm();
      if (d <= radius) candidates.push_back({static_cast<int>(i), static_cast<int>(j), d});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const PointMatch& a, const PointMatch& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.truth != b.truth ? a.truth < b.truth : a.detected < b.detected;
  });
  std::vector<bool> truth_used(truth.size(), false), detected_used(detected.size(), false);
  std::vector<PointMatch> matches;
  for (const PointMatch& m : candidates) {
    if (truth_used[m.truth] || detected_used[m.detected]) continue;
    truth_used[m.truth] = detected_used[m.detected] = true;
    matches.push_back(m);
  }
  std::sort(matches.begin(), matches.end(), [](const PointMatch& a, const PointMatch& b) { return a.truth < b.truth; });
  return matches;
}

void CollectEndpointOffsets(const LineSegments& detected, const LineSegment& truth, const bool use_end[2],
                            const EndpointOffsetOptions& options, EndpointOffsets* offsets) {
  const double length = truth.Length();
  if (!(length >= options.min_true_length)) return;
  const Eigen::Vector2d n = truth.Direction(), q = truth.Normal();
  const double min_cos = std::cos(options.max_angle_deg * M_PI / 180);
  double lowest = HUGE_VAL, highest = -HUGE_VAL;  // along n from truth.p0, over compatible detections
  for (const LineSegment& d : detected) {
    if (!(d.Length() > 0) || std::abs(d.Direction().dot(n)) < min_cos) continue;
    if (std::abs(q.dot(d.p0 - truth.p0)) > options.max_line_distance ||
        std::abs(q.dot(d.p1 - truth.p0)) > options.max_line_distance) {
      continue;
    }
    const double s0 = n.dot(d.p0 - truth.p0), s1 = n.dot(d.p1 - truth.p0);
    const double lo = std::min(s0, s1), hi = std::max(s0, s1);
    if (std::min(hi, length) - std::max(lo, 0.0) < std::min(options.min_overlap_px, length)) continue;
    lowest = std::min(lowest, lo);
    highest = std::max(highest, hi);
  }
  for (int e = 0; e < 2; ++e) {
    if (!use_end[e]) continue;
    ++offsets->ends;
    if (!std::isfinite(lowest)) {
      ++offsets->unmatched;
      continue;
    }
    // Outward at p0 is -n, at p1 it is +n.
    const double t = e == 0 ? -lowest : highest - length;
    if (std::abs(t) > options.max_abs_t) {
      ++offsets->gross;
      continue;
    }
    offsets->t.push_back(t);
  }
}

}  // namespace sfm

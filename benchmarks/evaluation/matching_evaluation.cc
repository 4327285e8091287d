#include "benchmarks/evaluation/matching_evaluation.h"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <glog/logging.h>
#include <opencv2/line_descriptor.hpp>

#include "geometry/epipolar.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_similarity.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "util/text_file.h"

namespace sfm {
namespace {


int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The line l = (a, b, c) scaled so that (a, b) is a unit vector; false at a degenerate line.
bool NormaliseLine(Eigen::Vector3d* l) {
  const double n = l->head<2>().norm();
  if (!(n > 1e-12) || !std::isfinite(n)) return false;
  *l /= n;
  return true;
}

// One way of SegmentsEpipolarConsistent: does segment b (image 2) meet the band between the
// epipolar lines F p0, F p1 of segment a's end-points, within `tolerance`?
bool BandMeetsSegment(const Eigen::Matrix3d& F, const LineSegment& a, const LineSegment& b, double tolerance) {
  Eigen::Vector3d l0 = F * a.p0.homogeneous(), l1 = F * a.p1.homogeneous();
  // An end-point at the epipole has no epipolar line: every line through the epipole is one.
  if (!NormaliseLine(&l0) || !NormaliseLine(&l1)) return true;
  const int samples = std::max(2, static_cast<int>(std::ceil(b.Length())) + 1);
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector2d x = b.p0 + (b.p1 - b.p0) * (static_cast<double>(k) / (samples - 1));
    const double d0 = l0.dot(x.homogeneous()), d1 = l1.dot(x.homogeneous());
    if (d0 * d1 <= 0 || std::min(std::abs(d0), std::abs(d1)) <= tolerance) return true;
  }
  return false;
}

// Reads whitespace-separated tokens of a file, one vector per non-empty line.
// The white-space separated words of each non-blank line (the VGG files have no comments).
Status ReadTokenLines(const std::string& path, std::vector<std::vector<std::string>>* rows) {
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  rows->clear();
  for (const DataLine& line : lines) rows->push_back(SplitWords(line.text));
  return Status::Ok();
}

// A VGG n-view file: one row per 3D feature, one column per view holding an index into that view's
// features (`features_per_view[v]` of them) or '*'. Calls assign(row, view, index) for each entry.
Status ReadNviewIndices(const std::string& path, const std::vector<size_t>& features_per_view,
                        const std::string& feature_name,
                        const std::function<Status(size_t row, size_t view, long index)>& assign) {
  std::vector<std::vector<std::string>> rows;
  SFM_RETURN_IF_ERROR(ReadTokenLines(path, &rows));
  for (size_t r = 0; r < rows.size(); ++r) {
    const std::string where = path + ":" + std::to_string(r + 1);
    if (rows[r].size() != features_per_view.size()) {
      return Status::Error(where + ": " + std::to_string(rows[r].size()) + " columns for " +
                           std::to_string(features_per_view.size()) + " views");
    }
    for (size_t v = 0; v < rows[r].size(); ++v) {
      if (rows[r][v] == "*") continue;
      char* end = nullptr;
      const long index = std::strtol(rows[r][v].c_str(), &end, 10);
      if (*end != '\0' || index < 0 || index >= static_cast<long>(features_per_view[v])) {
        return Status::Error(where + ": '" + rows[r][v] + "' is not a " + feature_name + " of view " +
                             std::to_string(v));
      }
      SFM_RETURN_IF_ERROR(assign(r, v, index));
    }
  }
  return Status::Ok();
}

}  // namespace

// ---- Features ------------------------------------------------------------------------------------

double ThreadCpuMs() {
  timespec t;
  CHECK_EQ(clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t), 0);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

FrameFeatures DetectFrameFeatures(const cv::Mat& undistorted_grey, const SegmentDetectorOptions& segment_options,
                                  const JunctionDetectorOptions& junction_options) {
  FrameFeatures features;
  const double start = ThreadCpuMs();
  features.segments = DetectLineSegments(undistorted_grey, segment_options);
  features.junctions = DetectJunctions(features.segments, junction_options);
  features.graph = BuildTopologyGraph(features.junctions);
  features.detect_ms = ThreadCpuMs() - start;
  return features;
}

// ---- Identities and verdicts ---------------------------------------------------------------------

std::vector<int> NearestWithin(const std::vector<Eigen::Vector2d>& points, const std::vector<Eigen::Vector2d>& targets,
                               double radius) {
  std::vector<int> nearest(points.size(), -1);
  for (size_t i = 0; i < points.size(); ++i) {
    double best = radius;
    for (size_t t = 0; t < targets.size(); ++t) {
      const double d = (points[i] - targets[t]).norm();
      if (d <= best) {
        best = d;
        nearest[i] = static_cast<int>(t);
      }
    }
  }
  return nearest;
}

std::vector<Eigen::Vector2d> JunctionLocations(const Junctions& junctions) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(junctions.size());
  for (const Junction& j : junctions) points.push_back(j.location);
  return points;
}

bool EpipolarConsistent(const Eigen::Matrix3d& F, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                        double tolerance) {
  return PointLineDistance(EpipolarLineInImage2(F, p1), p2) <= tolerance &&
         PointLineDistance(EpipolarLineInImage1(F, p2), p1) <= tolerance;
}

void MatchVerdicts::Add(const MatchVerdicts& o) {
  matches += o.matches;
  correct += o.correct;
  epipolar_wrong += o.epipolar_wrong;
  identity_wrong += o.identity_wrong;
  identity_known += o.identity_known;
  epipolar_wrong_same += o.epipolar_wrong_same;
  correct_known += o.correct_known;
}

MatchVerdicts JudgeMatches(const std::vector<std::pair<int, int>>& matches, const std::vector<Eigen::Vector2d>& points_a,
                           const std::vector<Eigen::Vector2d>& points_b, const Eigen::Matrix3d& F_true,
                           double tolerance, const SameFeature& same) {
  MatchVerdicts v;
  for (const auto& [ia, ib] : matches) {
    ++v.matches;
    const int identity = same ? same(ia, ib) : -1;
    if (identity >= 0) ++v.identity_known;
    if (!EpipolarConsistent(F_true, points_a.at(ia), points_b.at(ib), tolerance)) {
      ++v.epipolar_wrong;
      if (identity == 1) ++v.epipolar_wrong_same;
    } else if (identity == 0) {
      ++v.identity_wrong;
    } else {
      ++v.correct;
      if (identity == 1) ++v.correct_known;
    }
  }
  return v;
}

std::vector<std::pair<int, int>> MatchPairs(const std::vector<JunctionMatch>& matches) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(matches.size());
  for (const JunctionMatch& m : matches) pairs.emplace_back(m.index_a, m.index_b);
  return pairs;
}

FeatureRecall CountRecall(const std::vector<int>& truth_a, const std::vector<int>& truth_b,
                          const std::vector<std::pair<int, int>>& true_pairs,
                          const std::vector<std::pair<int, int>>& matches) {
  std::set<int> taken_a(truth_a.begin(), truth_a.end()), taken_b(truth_b.begin(), truth_b.end());
  std::set<std::pair<int, int>> joined;
  for (const auto& [ia, ib] : matches) {
    if (truth_a.at(ia) >= 0 && truth_b.at(ib) >= 0) joined.emplace(truth_a[ia], truth_b[ib]);
  }
  FeatureRecall recall;
  for (const auto& pair : true_pairs) {
    if (!taken_a.count(pair.first) || !taken_b.count(pair.second)) continue;
    ++recall.seen_both;
    if (joined.count(pair)) ++recall.matched;
  }
  return recall;
}

// ---- Generated sequences -------------------------------------------------------------------------

std::vector<std::vector<int>> TrueVerticesNearJunctions(const Junctions& junctions, const FrameTruth& frame,
                                                        double radius) {
  std::vector<std::vector<int>> near(junctions.size());
  for (size_t j = 0; j < junctions.size(); ++j) {
    std::vector<std::pair<double, int>> found;
    for (const VisibleVertex& v : frame.vertices) {
      const double d = (v.pixel - junctions[j].location).norm();
      if (d <= radius) found.emplace_back(d, v.vertex);
    }
    std::sort(found.begin(), found.end());
    for (const auto& [d, vertex] : found) near[j].push_back(vertex);
  }
  return near;
}

int SameTrueVertex(const std::vector<int>& near_a, const std::vector<int>& near_b) {
  if (near_a.empty() || near_b.empty()) return -1;
  for (int v : near_a) {
    if (std::find(near_b.begin(), near_b.end(), v) != near_b.end()) return 1;
  }
  return 0;
}

const char* MissReasonName(MissReason reason) {
  switch (reason) {
    case MissReason::kSegmentCount: return "different segment counts";
    case MissReason::kEpipolar: return "d or d' > R (or the pose band)";
    case MissReason::kCheirality: return "behind a camera (cheirality)";
    case MissReason::kNoShift: return "no shift passes (17), (36), (37)";
    case MissReason::kRule: return "rho > 0, lost in rule (38)";
    case MissReason::kNumReasons: break;
  }
  return "?";
}

void VertexMatchCounts::Add(const VertexMatchCounts& o) {
  pairs += o.pairs;
  matches += o.matches;
  associated += o.associated;
  same_vertex += o.same_vertex;
  same_nearest += o.same_nearest;
  seen_both += o.seen_both;
  seen_both_same_count += o.seen_both_same_count;
  matched += o.matched;
  matched_same_count += o.matched_same_count;
  matched_partial_only += o.matched_partial_only;
  for (int k = 0; k < static_cast<int>(MissReason::kNumReasons); ++k) misses[k] += o.misses[k];
}

VertexMatchCounts ScoreVertexMatches(const Junctions& a, const Junctions& b, const std::vector<std::vector<int>>& near_a,
                                     const std::vector<std::vector<int>>& near_b, const std::vector<JunctionMatch>& matches,
                                     const Eigen::Matrix3d& F, const MatchingOptions& options,
                                     const PairGeometry* geometry) {
  CHECK_EQ(near_a.size(), a.size());
  CHECK_EQ(near_b.size(), b.size());
  VertexMatchCounts c;
  c.pairs = 1;
  std::set<int> joined;
  std::set<int> joined_full;  // by a match of junctions with equal segment counts
  for (const JunctionMatch& m : matches) {
    ++c.matches;
    const std::vector<int>& va = near_a[m.index_a];
    const std::vector<int>& vb = near_b[m.index_b];
    const int same = SameTrueVertex(va, vb);
    if (same < 0) continue;
    ++c.associated;
    if (same == 1) ++c.same_vertex;
    if (same == 1 && va.front() == vb.front()) ++c.same_nearest;
    const bool full = a[m.index_a].NumSegments() == b[m.index_b].NumSegments();
    for (int v : va) {
      if (std::find(vb.begin(), vb.end(), v) == vb.end()) continue;
      joined.insert(v);
      if (full) joined_full.insert(v);
    }
  }
  // The junctions within the radius of each vertex, in each frame.
  std::map<int, std::vector<int>> at_a, at_b;
  for (size_t i = 0; i < a.size(); ++i) {
    for (int v : near_a[i]) at_a[v].push_back(static_cast<int>(i));
  }
  for (size_t i = 0; i < b.size(); ++i) {
    for (int v : near_b[i]) at_b[v].push_back(static_cast<int>(i));
  }
  const JunctionSimilarity similarity =
      geometry ? JunctionSimilarity(a, b, *geometry, options) : JunctionSimilarity(a, b, F, options);
  for (const auto& [vertex, list_a] : at_a) {
    const auto it = at_b.find(vertex);
    if (it == at_b.end()) continue;
    const std::vector<int>& list_b = it->second;
    ++c.seen_both;
    bool same_count = false;
    for (int ia : list_a) {
      for (int ib : list_b) same_count = same_count || a[ia].NumSegments() == b[ib].NumSegments();
    }
    if (same_count) ++c.seen_both_same_count;
    // A full match needs junctions of equal counts at the vertex, so joined_full implies same_count.
    if (joined_full.count(vertex)) ++c.matched_same_count;
    if (joined.count(vertex)) {
      ++c.matched;
      if (!joined_full.count(vertex)) ++c.matched_partial_only;
      continue;
    }
    // The reason, for the pair of junctions at the vertex that got farthest.
    MissReason best = MissReason::kSegmentCount;
    for (int ia : list_a) {
      for (int ib : list_b) {
        MissReason reason;
        if (a[ia].NumSegments() != b[ib].NumSegments()) {
          reason = MissReason::kSegmentCount;
        } else if (const JunctionSimilarity::Bands bands = similarity.BandsOf(ia, ib);
                   PointLineDistance(EpipolarLineInImage2(F, a[ia].location), b[ib].location) > bands.in_image2 ||
                   PointLineDistance(EpipolarLineInImage1(F, b[ib].location), a[ia].location) > bands.in_image1) {
          reason = MissReason::kEpipolar;
        } else if (!similarity.PassesCheirality(ia, ib)) {
          reason = MissReason::kCheirality;
        } else if (!similarity.Rho(ia, ib).Matched()) {
          reason = MissReason::kNoShift;
        } else {
          reason = MissReason::kRule;
        }
        best = std::max(best, reason);
      }
    }
    ++c.misses[static_cast<int>(best)];
  }
  return c;
}

// ---- VGG Corridor --------------------------------------------------------------------------------

Status ReadProjectionMatrix(const std::string& path, Eigen::Matrix<double, 3, 4>* P) {
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open");
  for (int k = 0; k < 12; ++k) {
    double value;
    if (!(in >> value) || !std::isfinite(value)) {
      return Status::Error(path + ": expected 12 numbers (a 3x4 projection matrix), found " + std::to_string(k));
    }
    (*P)(k / 4, k % 4) = value;
  }
  std::string extra;
  if (in >> extra) return Status::Error(path + ": more than 12 numbers");
  return Status::Ok();
}

Status ReadVggTruth(const std::string& directory, const SegmentJunctionOptions& junction_options, VggTruth* truth) {
  truth->views.clear();
  for (int i = 0;; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "bt.%03d", i);
    const std::string base = directory + "/" + stem;
    if (!std::filesystem::exists(base + ".pgm")) break;
    VggView view;
    SFM_RETURN_IF_ERROR(ReadProjectionMatrix(base + ".P", &view.P));
    SFM_RETURN_IF_ERROR(ReadVggLines(base + ".lines", &view.lines));
    view.line3d.assign(view.lines.size(), -1);
    if (std::filesystem::exists(base + ".corners")) {
      std::vector<std::vector<std::string>> rows;
      SFM_RETURN_IF_ERROR(ReadTokenLines(base + ".corners", &rows));
      for (size_t r = 0; r < rows.size(); ++r) {
        char* end_x = nullptr;
        char* end_y = nullptr;
        const double x = rows[r].size() == 2 ? std::strtod(rows[r][0].c_str(), &end_x) : NAN;
        const double y = rows[r].size() == 2 ? std::strtod(rows[r][1].c_str(), &end_y) : NAN;
        if (!std::isfinite(x) || !std::isfinite(y) || *end_x != '\0' || *end_y != '\0') {
          return Status::Error(base + ".corners:" + std::to_string(r + 1) + ": expected two numbers x y");
        }
        view.corners.emplace_back(x, y);
      }
    }
    view.corner_point3d.assign(view.corners.size(), -1);
    truth->views.push_back(std::move(view));
  }
  if (truth->views.empty()) return Status::Error(directory + ": no bt.NNN.pgm images");
  const std::string lines3d_path = directory + "/bt.l3d";
  if (std::filesystem::exists(lines3d_path)) {
    std::vector<std::vector<std::string>> rows;
    SFM_RETURN_IF_ERROR(ReadTokenLines(lines3d_path, &rows));
    for (size_t r = 0; r < rows.size(); ++r) {
      double v[6];
      for (int k = 0; k < 6; ++k) {
        char* end = nullptr;
        v[k] = rows[r].size() == 6 ? std::strtod(rows[r][k].c_str(), &end) : NAN;
        if (rows[r].size() != 6 || *end != '\0' || !std::isfinite(v[k])) {
          return Status::Error(lines3d_path + ":" + std::to_string(r + 1) + ": expected 6 numbers");
        }
      }
      truth->lines3d.emplace_back(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
    }
  }
  std::vector<size_t> lines_per_view, corners_per_view;
  for (const VggView& view : truth->views) {
    lines_per_view.push_back(view.lines.size());
    corners_per_view.push_back(view.corners.size());
  }
  const std::string tracks_path = directory + "/bt_original.nview-lines";
  if (std::filesystem::exists(tracks_path)) {
    SFM_RETURN_IF_ERROR(ReadNviewIndices(tracks_path, lines_per_view, "line", [&](size_t r, size_t v, long index) {
      if (r >= truth->lines3d.size()) {
        return Status::Error(tracks_path + ":" + std::to_string(r + 1) + ": row has no 3D line in " + lines3d_path);
      }
      truth->views[v].line3d[index] = static_cast<int>(r);
      return Status::Ok();
    }));
  }
  const std::string corner_tracks_path = directory + "/bt.nview-corners";
  if (std::filesystem::exists(corner_tracks_path)) {
    SFM_RETURN_IF_ERROR(
        ReadNviewIndices(corner_tracks_path, corners_per_view, "corner", [&](size_t r, size_t v, long index) {
          truth->views[v].corner_point3d[index] = static_cast<int>(r);
          return Status::Ok();
        }));
  }
  for (VggView& view : truth->views) {
    view.junctions = JunctionsFromSegments(view.lines, junction_options);
    for (const SegmentJunction& j : view.junctions) {
      std::set<int> ids;
      for (int s : j.segments) {
        if (view.line3d[s] >= 0) ids.insert(view.line3d[s]);
      }
      view.junction_lines3d.emplace_back(ids.begin(), ids.end());
    }
  }
  return Status::Ok();
}

std::vector<std::vector<int>> VggPointsNear(const VggView& view, const std::vector<Eigen::Vector2d>& points,
                                            double radius) {
  std::vector<std::vector<int>> near(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    std::vector<std::pair<double, int>> found;
    for (size_t c = 0; c < view.corners.size(); ++c) {
      const double d = (view.corners[c] - points[i]).norm();
      if (d <= radius && view.corner_point3d[c] >= 0) found.emplace_back(d, view.corner_point3d[c]);
    }
    std::sort(found.begin(), found.end());
    for (const auto& [d, point] : found) {
      if (std::find(near[i].begin(), near[i].end(), point) == near[i].end()) near[i].push_back(point);
    }
  }
  return near;
}

Eigen::Vector3d ProjectLine(const Eigen::Matrix<double, 3, 4>& P, const Eigen::Vector3d& X0, const Eigen::Vector3d& X1) {
  return (P * X0.homogeneous()).cross(P * X1.homogeneous());
}

int SameVggJunction(const VggView& a, int junction_a, const VggView& b, int junction_b) {
  const std::vector<int>& la = a.junction_lines3d.at(junction_a);
  const std::vector<int>& lb = b.junction_lines3d.at(junction_b);
  if (la.size() < 2 || lb.size() < 2) return -1;
  std::vector<int> common;
  std::set_intersection(la.begin(), la.end(), lb.begin(), lb.end(), std::back_inserter(common));
  return common.size() >= 2 ? 1 : 0;
}

// ---- Line matches --------------------------------------------------------------------------------

std::vector<int> AssociateSegments(const LineSegments& detected, const LineSegments& truth,
                                   const LineAssociationOptions& options) {
  const double min_cos = std::cos(options.max_angle_deg * M_PI / 180);
  std::vector<int> result(detected.size(), -1);
  for (size_t i = 0; i < detected.size(); ++i) {
    const LineSegment& d = detected[i];
    const double length = d.Length();
    if (!(length > 0)) continue;
    double best = options.min_overlap * length;
    for (size_t t = 0; t < truth.size(); ++t) {
      const LineSegment& g = truth[t];
      if (!(g.Length() > 0)) continue;
      const Eigen::Vector2d n = g.Direction(), q = g.Normal();
      if (std::abs(n.dot(d.Direction())) < min_cos) continue;
      if (std::abs(q.dot(d.p0 - g.p0)) > options.max_distance || std::abs(q.dot(d.p1 - g.p0)) > options.max_distance) {
        continue;
      }
      const double u0 = n.dot(d.p0 - g.p0), u1 = n.dot(d.p1 - g.p0);
      const double overlap = std::min(std::max(u0, u1), g.Length()) - std::max(std::min(u0, u1), 0.0);
      if (overlap >= best) {
        best = overlap;
        result[i] = static_cast<int>(t);
      }
    }
  }
  return result;
}

bool SegmentsEpipolarConsistent(const Eigen::Matrix3d& F, const LineSegment& a, const LineSegment& b,
                                double tolerance) {
  return BandMeetsSegment(F, a, b, tolerance) && BandMeetsSegment(F.transpose(), b, a, tolerance);
}

std::vector<int> WireframeLineIds(const Wireframe& wireframe) {
  const int n = static_cast<int>(wireframe.edges.size());
  std::vector<int> parent(n);
  for (int i = 0; i < n; ++i) parent[i] = i;
  constexpr double kTolerance = 1e-3;  // m
  auto on_line = [&](const WireEdge& e, const Eigen::Vector3d& p) {
    const Eigen::Vector3d a = wireframe.vertices[e.vertex_a], b = wireframe.vertices[e.vertex_b];
    const Eigen::Vector3d d = (b - a).normalized();
    return ((p - a) - d * d.dot(p - a)).norm() <= kTolerance;
  };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const WireEdge& e = wireframe.edges[j];
      if (on_line(wireframe.edges[i], wireframe.vertices[e.vertex_a]) &&
          on_line(wireframe.edges[i], wireframe.vertices[e.vertex_b])) {
        parent[Find(parent, j)] = Find(parent, i);
      }
    }
  }
  std::vector<int> id(n);
  for (int i = 0; i < n; ++i) id[i] = Find(parent, i);
  return id;
}

void TrueLinesOfFrame(const FrameTruth& frame, const std::vector<int>& edge_line_id, LineSegments* lines,
                      std::vector<int>* line_ids) {
  lines->clear();
  line_ids->clear();
  for (const VisibleSegment& s : frame.segments) {
    LineSegment segment;
    segment.p0 = s.pixel[0];
    segment.p1 = s.pixel[1];
    lines->push_back(segment);
    line_ids->push_back(edge_line_id.at(s.edge));
  }
}

void LineMatchScore::Add(const LineMatchScore& o) {
  verdicts.Add(o.verdicts);
  seen_both += o.seen_both;
  matched += o.matched;
}

bool SegmentOnLine(const LineSegment& s, const Eigen::Vector3d& line, const LineAssociationOptions& options) {
  Eigen::Vector3d l = line;
  if (!NormaliseLine(&l) || !(s.Length() > 0)) return false;
  const Eigen::Vector2d line_direction(-l.y(), l.x());
  return std::abs(l.dot(s.p0.homogeneous())) <= options.max_distance &&
         std::abs(l.dot(s.p1.homogeneous())) <= options.max_distance &&
         std::abs(line_direction.dot(s.Direction())) >= std::cos(options.max_angle_deg * M_PI / 180);
}

LineMatchScore ScoreLineMatches(const LineSegments& a, const LineSegments& b,
                                const std::vector<std::pair<int, int>>& matches, const std::vector<int>& id_a,
                                const std::vector<int>& id_b, const LineOfId& line_in_a, const LineOfId& line_in_b,
                                const Eigen::Matrix3d& F_true, double tolerance) {
  const LineAssociationOptions on_line;
  LineMatchScore score;
  for (const auto& [ia, ib] : matches) {
    MatchVerdicts& v = score.verdicts;
    ++v.matches;
    const int la = id_a.at(ia), lb = id_b.at(ib);
    if (la >= 0 || lb >= 0) ++v.identity_known;
    if (!SegmentsEpipolarConsistent(F_true, a[ia], b[ib], tolerance)) {
      ++v.epipolar_wrong;
    } else if ((la >= 0 && !SegmentOnLine(b[ib], line_in_b(la), on_line)) ||
               (lb >= 0 && !SegmentOnLine(a[ia], line_in_a(lb), on_line))) {
      ++v.identity_wrong;
    } else {
      ++v.correct;
      if (la >= 0 || lb >= 0) ++v.correct_known;
    }
  }
  std::set<int> ids(id_a.begin(), id_a.end());
  std::vector<std::pair<int, int>> true_pairs;
  for (int id : ids) {
    if (id >= 0) true_pairs.emplace_back(id, id);
  }
  const FeatureRecall recall = CountRecall(id_a, id_b, true_pairs, matches);
  score.seen_both = recall.seen_both;
  score.matched = recall.matched;
  return score;
}

LbdFeatures DetectLbd(const cv::Mat& grey, double min_length) {
  using namespace cv::line_descriptor;
  static const cv::Ptr<LSDDetector> lsd = LSDDetector::createLSDDetector();
  static const cv::Ptr<BinaryDescriptor> lbd = BinaryDescriptor::createBinaryDescriptor();
  LbdFeatures features;
  const double start = ThreadCpuMs();
  std::vector<KeyLine> detected, kept;
  lsd->detect(grey, detected, /*scale=*/2, /*numOctaves=*/1);
  for (const KeyLine& k : detected) {
    if (k.octave == 0 && k.lineLength >= min_length) {
      kept.push_back(k);
      kept.back().class_id = static_cast<int>(kept.size()) - 1;
    }
  }
  lbd->compute(grey, kept, features.descriptors);
  features.detect_ms = ThreadCpuMs() - start;
  CHECK_EQ(features.descriptors.rows, static_cast<int>(kept.size()));
  for (const KeyLine& k : kept) {
    LineSegment s;
    s.p0 = Eigen::Vector2d(k.startPointX, k.startPointY);
    s.p1 = Eigen::Vector2d(k.endPointX, k.endPointY);
    features.segments.push_back(s);
  }
  return features;
}

std::vector<std::pair<int, int>> MatchLbd(const cv::Mat& descriptors_a, const cv::Mat& descriptors_b, bool mutual) {
  using namespace cv::line_descriptor;
  static const cv::Ptr<BinaryDescriptorMatcher> matcher = BinaryDescriptorMatcher::createBinaryDescriptorMatcher();
  std::vector<std::pair<int, int>> pairs;
  if (descriptors_a.empty() || descriptors_b.empty()) return pairs;
  std::vector<cv::DMatch> forward, backward;
  matcher->match(descriptors_a, descriptors_b, forward);
  if (mutual) matcher->match(descriptors_b, descriptors_a, backward);
  std::vector<int> best_of_b(descriptors_b.rows, -1);
  for (const cv::DMatch& m : backward) best_of_b.at(m.queryIdx) = m.trainIdx;
  for (const cv::DMatch& m : forward) {
    if (mutual && best_of_b.at(m.trainIdx) != m.queryIdx) continue;
    pairs.emplace_back(m.queryIdx, m.trainIdx);
  }
  return pairs;
}

}  // namespace sfm

// The measurements and the report of benchmark_junctions (junction_benchmark.h).
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/pair_probability.h"
#include "frontend/junctions/undistorted_junctions.h"
#include "frontend/segments/endpoint_fit.h"
#include "frontend/segments/segment_detector.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "frontend/segments/undistorted_segments.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/sequence_writer.h"
#include "benchmarks/evaluation/junction_evaluation.h"
#include "pipeline/overlay/junction_overlay.h"
#include "benchmarks/evaluation/table_format.h"
#include "benchmarks/junctions/junction_benchmark.h"

namespace sfm {
namespace {

const SegmentJunctionOptions kGtDefaults;
const EndpointOffsetOptions kOffsetDefaults;

using Clock = std::chrono::steady_clock;
constexpr int kNumTypes = 6;
constexpr JunctionType kTypes[kNumTypes] = {JunctionType::kL, JunctionType::kY, JunctionType::kArrow,
                                            JunctionType::kT, JunctionType::kX, JunctionType::kN};

// Why a detectable vertex was missed, first reason that applies.
enum MissKind {
  kCrowded,        // another true junction (vertex or occlusion T) within 2 x radius
  kEdgesMissing,   // fewer than two of its long edges have a detected segment on them
  kEndsFar,        // fewer than two of those detections reach within max_gap_px of the vertex
  kNotJoined,      // at least two do, yet no junction within the radius
  kNumMissKinds
};
const char* const kMissNames[kNumMissKinds] = {
    "crowded: another true junction within 2 x radius",
    "edges missing: fewer than 2 long edges have a detected segment on them",
    "ends far: fewer than 2 of those segments end within max_gap_px of the vertex",
    "not joined: 2 or more segments end near, no junction within the radius"};

// No other true junction (vertex or occlusion T) within 2 x radius of p.
bool Isolated(const JunctionBenchmarkOptions& bench, const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& any_truth) {
  for (const Eigen::Vector2d& q : any_truth) {
    const double d = (p - q).norm();
    if (d > 1e-6 && d <= 2 * bench.radius) return false;
  }
  return true;
}

// The segment-level reason (kEdgesMissing, kEndsFar or kNotJoined), crowded or not.
MissKind WhySegmentsMissed(const TrueVertexJunction& v, const LineSegments& segments, double max_gap);

MissKind WhyMissed(const JunctionBenchmarkOptions& bench, const TrueVertexJunction& v, const std::vector<Eigen::Vector2d>& any_truth,
                   const LineSegments& segments, double max_gap) {
  if (!Isolated(bench, v.location, any_truth)) return kCrowded;
  return WhySegmentsMissed(v, segments, max_gap);
}

// Crowded misses, split: the segment-level reasons, and "not joined" split into a detection within
// the radius that the one-to-one matching gave to another true junction, and none.
constexpr int kNumCrowdedKinds = 4;
const char* const kCrowdedNames[kNumCrowdedKinds] = {
    "crowded, edges missing", "crowded, ends far",
    "crowded, a detection within the radius, matched to another true junction",
    "crowded, segments end near, no detection within the radius"};

MissKind WhySegmentsMissed(const TrueVertexJunction& v, const LineSegments& segments, double max_gap) {
  EndpointOffsetOptions options;
  options.max_abs_t = 1e9;
  options.min_true_length = 0;
  int detected = 0, close = 0;
  for (const Eigen::Vector2d& far : v.long_edge_ends) {
    LineSegment edge;
    edge.p0 = v.location;
    edge.p1 = far;
    EndpointOffsets offsets;
    const bool at_vertex[2] = {true, false};
    CollectEndpointOffsets(segments, edge, at_vertex, options, &offsets);
    if (offsets.t.empty()) continue;
    ++detected;
    if (offsets.t[0] >= -max_gap) ++close;
  }
  if (detected < 2) return kEdgesMissing;
  if (close < 2) return kEndsFar;
  return kNotJoined;
}

// Mean absolute grey-level step across the segment a -> b, sampled every pixel 3 px in from each
// end, 2 px to each side (as EdgeContrasts); -1 without samples.
double StepAcross(const cv::Mat& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double length = (b - a).norm();
  if (image.empty() || length < 7) return -1;
  const Eigen::Vector2d d = (b - a) / length, n(-d.y(), d.x());
  double sum = 0;
  int count = 0;
  for (double s = 3; s <= length - 3; s += 1) {
    const Eigen::Vector2d p = a + s * d, l = p - 2 * n, r = p + 2 * n;
    if (l.x() < 0 || r.x() < 0 || l.y() < 0 || r.y() < 0 || l.x() > image.cols - 2 || r.x() > image.cols - 2 ||
        l.y() > image.rows - 2 || r.y() > image.rows - 2) continue;
    auto at = [&](const Eigen::Vector2d& q) {
      const int x = static_cast<int>(q.x()), y = static_cast<int>(q.y());
      const double fx = q.x() - x, fy = q.y() - y;
      return (1 - fx) * (1 - fy) * image.at<uchar>(y, x) + fx * (1 - fy) * image.at<uchar>(y, x + 1) +
             (1 - fx) * fy * image.at<uchar>(y + 1, x) + fx * fy * image.at<uchar>(y + 1, x + 1);
    };
    sum += std::abs(at(r) - at(l));
    ++count;
  }
  return count ? sum / count : -1;
}

// The detection closest to lying on the true edge a -> b: among those within 10 degrees and 4 px of
// its line that overlap it, the one with the largest overlap. Its angle (deg), largest end-point
// distance to the true line (px) and overlap (px); overlap 0 when there is none.
struct Candidate {
  double angle = 0, distance = 0, overlap = 0, length = 0;
};
Candidate ClosestDetection(const LineSegments& segments, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  LineSegment edge;
  edge.p0 = a;
  edge.p1 = b;
  const Eigen::Vector2d n = edge.Direction(), q = edge.Normal();
  const double length = edge.Length();
  Candidate best;
  for (const LineSegment& d : segments) {
    if (!(d.Length() > 0)) continue;
    const double angle = std::acos(std::min(1.0, std::abs(d.Direction().dot(n)))) * 180 / M_PI;
    const double distance = std::max(std::abs(q.dot(d.p0 - a)), std::abs(q.dot(d.p1 - a)));
    if (angle > 10 || distance > 4) continue;
    const double s0 = n.dot(d.p0 - a), s1 = n.dot(d.p1 - a);
    const double overlap = std::min(std::max(s0, s1), length) - std::max(std::min(s0, s1), 0.0);
    if (overlap > best.overlap) best = {angle, distance, overlap, d.Length()};
  }
  return best;
}

double Ms(Clock::time_point since) { return std::chrono::duration<double, std::milli>(Clock::now() - since).count(); }

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}


using Method = JunctionBenchmarkMethod;

// What one detector did on one set of generated frames.
// Stricter readings of "detectable", reported beside the main one.
// 3 and 4: the contrast-visible readings (counted edges also of measurable contrast in the
// noise-free image), at min_contrast_sigmas x noise_sigma and at the segment detectors' high
// contrast threshold.
constexpr int kNumVariants = 5;
std::string VariantName(const JunctionBenchmarkOptions& bench, int k) {
  switch (k) {
    case 0: return "main, and isolated: no other true junction within 2 x radius";
    case 1: return "at least two edges of at least 20 px";
    case 2: return "at least two edges of at least 20 px, isolated";
    case 3: {
      char text[200];
      std::snprintf(text, sizeof text,
                    "contrast-visible: main, counting only edges with a step >= %g sigma = %g grey levels",
                    bench.min_contrast_sigmas, bench.min_contrast_sigmas * bench.noise_sigma);
      return text;
    }
    default: {
      char text[200];
      std::snprintf(text, sizeof text, "main, counting only edges with a step >= %g grey levels (detector's high threshold)",
                    bench.edge_contrast_high);
      return text;
    }
  }
}

// Rings of distance from the principal point (undistorted px) for the recall by radius: where lens
// distortion stretches the undistorted image most (the periphery), recall can differ.
constexpr int kNumRings = 5;
constexpr double kRingEdges[kNumRings + 1] = {0, 100, 175, 250, 325, 1e9};
int RingOf(const Camera& camera, const Eigen::Vector2d& p) {
  const double r = std::hypot(p.x() - camera.cx, p.y() - camera.cy);
  int k = 0;
  while (k + 1 < kNumRings && r >= kRingEdges[k + 1]) ++k;
  return k;
}

// Rings of angle from the optical axis (degrees) for the recall by angle: lenses of different focal
// length and model compared where they look (47 degrees: the 150 degree fisheye's canvas stretch 2.2).
constexpr int kNumAngleRings = 5;
constexpr double kAngleRingEdges[kNumAngleRings + 1] = {0, 15, 30, 40, 47, 90};
int AngleRingOf(const Camera& camera, const Eigen::Vector2d& p) {
  const double degrees =
      std::atan(std::hypot((p.x() - camera.cx) / camera.fx, (p.y() - camera.cy) / camera.fy)) * 180 / M_PI;
  int k = 0;
  while (k + 1 < kNumAngleRings && degrees >= kAngleRingEdges[k + 1]) ++k;
  return k;
}

struct GeneratedStats {
  std::array<int, kNumRings> ring_detectable{}, ring_found{};
  std::array<int, kNumAngleRings> angle_detectable{}, angle_found{};
  std::array<std::array<int, kNumMissKinds>, kNumRings> ring_misses{};  // by WhyMissed
  std::array<double, kNumRings> ring_stretch{};  // the undistortion's radial stretch at the ring's middle
  std::array<int, kNumVariants> variant_count{}, variant_found{};
  std::array<std::vector<double>, kNumVariants> variant_errors;
  int frames = 0;
  int detectable = 0, detectable_found = 0;
  int detectable_near = 0;  // literal reading: any detection within radius (not exclusive)
  int visible = 0, visible_found = 0;  // every visible vertex junction
  int occlusions = 0, occlusions_found = 0;  // occlusion T's (occluded edge part >= min_edge_px)
  int detected = 0, detected_valid = 0, detected_correct = 0;  // correct: a true vertex or occlusion T
  int segments = 0;
  double segment_ms = 0, junction_ms = 0;
  std::vector<double> errors;  // px, detectable vertices found
  std::array<int, kNumTypes> true_by_type{}, found_by_type{};  // detectable vertices, by true type
  std::array<int, kNumTypes> detected_by_type{}, detected_vertex_by_type{}, detected_correct_by_type{};
  std::array<std::array<int, kNumTypes>, kNumTypes> confusion{};  // [true type][detected type], found detectable
  EndpointOffsets vertex_ends, occlusion_ends;
  std::array<int, kNumMissKinds> misses{};  // missed detectable vertices by MissKind
  std::array<int, kNumCrowdedKinds> crowded{};  // crowded misses by kCrowdedNames
  std::array<int, kNumMissKinds> contrast_misses{};  // missed contrast-visible vertices by MissKind
  bool has_contrast = false;  // a noise-free twin was measured

  void Add(const GeneratedStats& o) {
    for (int k = 0; k < kNumRings; ++k) {
      ring_detectable[k] += o.ring_detectable[k];
      ring_found[k] += o.ring_found[k];
      for (int j = 0; j < kNumMissKinds; ++j) ring_misses[k][j] += o.ring_misses[k][j];
    }
    for (int k = 0; k < kNumAngleRings; ++k) {
      angle_detectable[k] += o.angle_detectable[k];
      angle_found[k] += o.angle_found[k];
    }
    for (int k = 0; k < kNumMissKinds; ++k) misses[k] += o.misses[k];
    for (int k = 0; k < kNumCrowdedKinds; ++k) crowded[k] += o.crowded[k];
    for (int k = 0; k < kNumMissKinds; ++k) contrast_misses[k] += o.contrast_misses[k];
    has_contrast = has_contrast || o.has_contrast;
    for (int k = 0; k < kNumVariants; ++k) {
      variant_count[k] += o.variant_count[k];
      variant_found[k] += o.variant_found[k];
      variant_errors[k].insert(variant_errors[k].end(), o.variant_errors[k].begin(), o.variant_errors[k].end());
    }
    frames += o.frames;
    detectable += o.detectable;
    detectable_found += o.detectable_found;
    detectable_near += o.detectable_near;
    visible += o.visible;
    occlusions += o.occlusions;
    occlusions_found += o.occlusions_found;
    visible_found += o.visible_found;
    detected += o.detected;
    detected_valid += o.detected_valid;
    detected_correct += o.detected_correct;
    segments += o.segments;
    segment_ms += o.segment_ms;
    junction_ms += o.junction_ms;
    errors.insert(errors.end(), o.errors.begin(), o.errors.end());
    for (int i = 0; i < kNumTypes; ++i) {
      true_by_type[i] += o.true_by_type[i];
      found_by_type[i] += o.found_by_type[i];
      detected_by_type[i] += o.detected_by_type[i];
      detected_vertex_by_type[i] += o.detected_vertex_by_type[i];
      detected_correct_by_type[i] += o.detected_correct_by_type[i];
      for (int j = 0; j < kNumTypes; ++j) confusion[i][j] += o.confusion[i][j];
    }
    for (auto [to, from] : {std::pair{&vertex_ends, &o.vertex_ends}, std::pair{&occlusion_ends, &o.occlusion_ends}}) {
      to->t.insert(to->t.end(), from->t.begin(), from->t.end());
      to->ends += from->ends;
      to->unmatched += from->unmatched;
      to->gross += from->gross;
    }
  }
};

// Ground-truth junctions of the VGG images for a range of contact distances: how far apart the
// ends of GT segments that meet at a corner are.
std::string VggContactTable(const JunctionBenchmarkOptions& bench, const std::string& directory) {
  const double contacts[] = {1, 2, 3, 4, 5, 6, 8, 10};
  int totals[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0;; ++i) {
    char path[64];
    std::snprintf(path, sizeof path, "/bt.%03d.lines", i);
    LineSegments segments;
    if (!std::filesystem::exists(directory + path) || !ReadVggLines(directory + path, &segments).ok()) break;
    for (int c = 0; c < 8; ++c) {
      SegmentJunctionOptions options;
      options.contact_px = contacts[c];
      options.min_angle_deg = bench.gt_min_angle_deg;
      totals[c] += static_cast<int>(JunctionsFromSegments(segments, options).size());
    }
  }
  std::ostringstream table;
  table << "| contact (px) |";
  for (double c : contacts) table << " " << c << " |";
  table << "\n|---|---|---|---|---|---|---|---|---|\n| GT junctions |";
  for (int total : totals) table << " " << total << " |";
  table << "\n";
  return table.str();
}

struct VggStats {
  int images = 0, gt_segments = 0, gt_junctions = 0, gt_found = 0, detected = 0, detected_correct = 0;
  int detected_border = 0, correct_border = 0;  // detections within the radius of the image border
  int detected_on_gt = 0, correct_on_gt = 0;     // detections with two or more segments on GT segments
  std::vector<double> errors, dx, dy;
  std::array<int, kNumTypes> gt_by_type{}, gt_found_by_type{}, detected_by_type{}, detected_correct_by_type{};
  EndpointOffsets ends;
  double ms = 0;
};

std::vector<Eigen::Vector2d> Locations(const Junctions& junctions) {
  std::vector<Eigen::Vector2d> points;
  for (const Junction& j : junctions) points.push_back(j.location);
  return points;
}

// Undistorted pixels whose distorted position lies in the stored image, `margin` px inside it:
// where the undistorted image shows the scene and not the black fill. With `in_image`, also
// `margin` px inside the undistorted image itself (without distortion the same condition; with
// barrel distortion the undistorted frame's border maps well inside the stored image, so without
// it vertices on the undistorted image's edge would count, which the detector cannot see).
// The mask covers `size` pixels from K's pixel -offset (the image itself, or with
// --undistort_full_view and --truth_in_image=false the full-view canvas: the wider reading).
cv::Mat ValidMask(const Camera& camera, double margin, bool in_image, const Eigen::Vector2d& offset,
                  const cv::Size& size) {
  cv::Mat mask(size.height, size.width, CV_8U, cv::Scalar(255));
  for (int my = 0; my < size.height; ++my) {
    for (int mx = 0; mx < size.width; ++mx) {
      const double x = mx - offset.x(), y = my - offset.y();
      const Eigen::Vector2d d = camera.DistortPixel(Eigen::Vector2d(x, y));
      bool inside = d.x() >= margin && d.y() >= margin && d.x() <= camera.width - 1 - margin &&
                    d.y() <= camera.height - 1 - margin;
      if (in_image) {
        inside = inside && x >= margin && y >= margin && x <= camera.width - 1 - margin &&
                 y <= camera.height - 1 - margin;
      }
      mask.at<uchar>(my, mx) = inside ? 255 : 0;
    }
  }
  return mask;
}

bool InMask(const cv::Mat& mask, const Eigen::Vector2d& p) {
  const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
  return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<uchar>(y, x) != 0;
}

Status WritePng(const std::string& path, const cv::Mat& image) {
  std::vector<uchar> png;
  if (!cv::imencode(".png", image, png)) return Status::Error(path + ": PNG encoding failed");
  return WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

// The standard generated sequences: name and generator options.
std::vector<std::pair<std::string, GeneratorOptions>> StandardSequences(int frames) {
  std::vector<std::pair<std::string, GeneratorOptions>> sequences;
  GeneratorOptions corridor;
  corridor.scene.type = SceneType::kCorridor;
  corridor.trajectory.type = TrajectoryType::kStraight;
  corridor.trajectory.num_frames = frames;
  corridor.seed = 11;
  sequences.emplace_back("corridor", corridor);
  GeneratorOptions room;
  room.scene.type = SceneType::kRoom;
  room.trajectory.type = TrajectoryType::kLoop;
  room.trajectory.num_frames = frames;
  room.seed = 12;
  sequences.emplace_back("room", room);
  GeneratorOptions distorted = corridor;
  distorted.trajectory.type = TrajectoryType::kTurns;
  distorted.camera.distortion = {-0.25, 0.07, 0.0005, -0.0005, 0};
  distorted.seed = 13;
  sequences.emplace_back("corridor-distorted", distorted);
  return sequences;
}

// Crop for --miss_dir: 40 x 40 px around the vertex, drawn 8x: the grey levels stretched to the
// crop's range on the left, the overlay (segments, the given junctions, the true long edges, true
// junctions, the missed vertex) on the right (18 black rows on top hold its legend).
Status WriteMissCrop(const std::string& path, const TrueVertexJunction& v,
                     const std::vector<Eigen::Vector2d>& any_truth, const cv::Mat& grey,
                     const LineSegments& segments, const Junctions& junctions, LineSegments edges) {
  const int half = 20, legend_rows = 18;
  const cv::Rect box = cv::Rect(static_cast<int>(v.location.x()) - half, static_cast<int>(v.location.y()) - half,
                                2 * half, 2 * half) & cv::Rect(0, 0, grey.cols, grey.rows);
  cv::Mat padded(box.height + legend_rows, box.width, CV_8U, cv::Scalar(0));
  grey(box).copyTo(padded(cv::Rect(0, legend_rows, box.width, box.height)));
  const Eigen::Vector2d origin(box.x, box.y - legend_rows);
  LineSegments shifted = segments;
  for (LineSegment& s : shifted) s.p0 -= origin, s.p1 -= origin;
  for (LineSegment& s : edges) s.p0 -= origin, s.p1 -= origin;
  Junctions moved = junctions;
  for (Junction& j : moved) {
    j.location -= origin;
    for (JunctionSegment& js : j.segments) js.end -= origin;
  }
  std::vector<Eigen::Vector2d> others;
  for (const Eigen::Vector2d& q : any_truth) others.push_back(q - origin);
  const cv::Mat overlay = DrawJunctionOverlay(padded, shifted, moved, 8,
                                              {{{}, edges, cv::Scalar(0, 140, 255), "true long edges"},
                                               {others, {}, cv::Scalar(0, 255, 0), "true junctions"},
                                               {{v.location - origin}, {}, cv::Scalar(255, 255, 255), "missed"}});
  cv::Mat stretched;
  cv::normalize(padded, stretched, 0, 255, cv::NORM_MINMAX, CV_8U, padded > 0);
  cv::resize(stretched, stretched, cv::Size(), 8, 8, cv::INTER_NEAREST);
  cv::cvtColor(stretched, stretched, cv::COLOR_GRAY2BGR);
  cv::Mat both;
  cv::hconcat(stretched, overlay, both);
  return WritePng(path, both);
}

// One missed vertex whose edges have no segment, for --miss_dir: a row per long edge in misses.csv
// and a crop of the image around it.
Status WriteMiss(const JunctionBenchmarkOptions& bench, const std::string& tag, int frame, const TrueVertexJunction& v, bool crowded,
                 const std::vector<Eigen::Vector2d>& any_truth, const cv::Mat& grey, const cv::Mat& clean,
                 const LineSegments& segments, const SegmentDetectorOptions& detector) {
  static int counter = 0;  // numbers the misses of the whole run (one run per process)
  // The same detector without the length cut and the NFA (0), without the length cut (1), without
  // the NFA (2): which of the two removed the edge's segment, if either.
  std::array<LineSegments, 3> relaxed;
  for (int k = 0; k < 3; ++k) {
    SegmentDetectorOptions o = detector;
    if (k != 2) o.min_length = 3;
    if (k != 1) o.fast.log10_nfa_max = 1e9;
    relaxed[k] = DetectLineSegments(grey, o);
  }
  const int id = counter++;
  const std::string csv_path = bench.miss_dir + "/misses.csv";
  const bool fresh = id == 0;
  FILE* csv = std::fopen(csv_path.c_str(), fresh ? "w" : "a");
  if (csv == nullptr) return Status::Error(csv_path + ": cannot open");
  if (fresh) {
    std::fprintf(csv, "id,tag,frame,vx,vy,crowded,nearest_truth_px,edge,length_px,step,cand_angle_deg,cand_dist_px,"
                      "cand_overlap_px,cand_length_px,relaxed_all,relaxed_length,relaxed_nfa\n");
  }
  double nearest = HUGE_VAL;
  for (const Eigen::Vector2d& q : any_truth) {
    const double d = (q - v.location).norm();
    if (d > 1e-6) nearest = std::min(nearest, d);
  }
  LineSegments edges;
  for (size_t e = 0; e < v.long_edge_ends.size(); ++e) {
    const Eigen::Vector2d& far = v.long_edge_ends[e];
    const Candidate c = ClosestDetection(segments, v.location, far);
    // Whether the edge would have a segment on it (as the "edges missing" test reads it) without
    // the length cut and the NFA, without the length cut alone, without the NFA alone.
    auto on_edge = [&](const LineSegments& relaxed) {
      LineSegment edge;
      edge.p0 = v.location;
      edge.p1 = far;
      EndpointOffsetOptions options;
      options.max_abs_t = 1e9;
      options.min_true_length = 0;
      EndpointOffsets offsets;
      const bool one[2] = {true, false};
      CollectEndpointOffsets(relaxed, edge, one, options, &offsets);
      return offsets.t.empty() ? 0 : 1;
    };
    std::fprintf(csv, "%d,%s,%d,%.2f,%.2f,%d,%.2f,%zu,%.1f,%.1f,%.2f,%.2f,%.1f,%.1f,%d,%d,%d\n", id, tag.c_str(), frame,
                 v.location.x(), v.location.y(), crowded ? 1 : 0, nearest, e, (far - v.location).norm(),
                 StepAcross(clean, v.location, far), c.angle, c.distance, c.overlap, c.length, on_edge(relaxed[0]),
                 on_edge(relaxed[1]), on_edge(relaxed[2]));
    LineSegment edge;
    edge.p0 = v.location;
    edge.p1 = far;
    edges.push_back(edge);
  }
  std::fclose(csv);
  char name[128];
  std::snprintf(name, sizeof name, "/%04d_%s_%03d.png", id, tag.c_str(), frame);
  return WriteMissCrop(bench.miss_dir + name, v, any_truth, grey, segments, {}, edges);
}

// One missed vertex whose segments end near it, for --miss_dir: in notjoined.csv, a row per pair of
// segments on two of its long edges: the pair test's verdict with the default options, the eq. (6)
// point's distance from the vertex, the t of each segment, and for each segment the detected junction
// that took it closest to the vertex (its distance from the vertex and its segments' indices, "-" if
// none): which reading won over the vertex's own pair.
Status WriteNotJoined(const JunctionBenchmarkOptions& bench, const std::string& tag, int frame, const TrueVertexJunction& v, bool crowded,
                      const std::vector<Eigen::Vector2d>& any_truth, const cv::Mat& grey,
                      const LineSegments& segments, const Junctions& junctions,
                      const JunctionDetectorOptions& options) {
  static int counter = 0;
  const int id = counter++;
  const std::string csv_path = bench.miss_dir + "/notjoined.csv";
  FILE* csv = std::fopen(csv_path.c_str(), id == 0 ? "w" : "a");
  if (csv == nullptr) return Status::Error(csv_path + ": cannot open");
  if (id == 0) std::fprintf(csv, "id,tag,frame,vx,vy,crowded,edge_a,edge_b,seg_a,seg_b,passes,probability,location_error_px,t_a,t_b,angle_deg,len_a,len_b,taken_a_px,taken_a_by,taken_b_px,taken_b_by\n");
  // The segments on each long edge (same line within 1 px at both ends, 3 degrees, overlapping).
  std::vector<std::vector<int>> on_edge(v.long_edge_ends.size());
  for (size_t e = 0; e < v.long_edge_ends.size(); ++e) {
    LineSegment edge;
    edge.p0 = v.location;
    edge.p1 = v.long_edge_ends[e];
    EndpointOffsetOptions o;
    o.max_abs_t = 1e9;
    o.min_true_length = 0;
    for (size_t k = 0; k < segments.size(); ++k) {
      EndpointOffsets offsets;
      const bool one[2] = {true, false};
      CollectEndpointOffsets({segments[k]}, edge, one, o, &offsets);
      if (!offsets.t.empty() && offsets.t[0] >= -options.max_gap_px) on_edge[e].push_back(static_cast<int>(k));
    }
  }
  std::vector<SegmentLine> lines;
  for (const LineSegment& s : segments) lines.emplace_back(s);
  JunctionDetectorOptions loose = options;
  loose.min_probability = 1e-12;
  loose.max_gap_px = 1e9;
  for (size_t a = 0; a < on_edge.size(); ++a) {
    for (size_t b = a + 1; b < on_edge.size(); ++b) {
      for (int sa : on_edge[a]) {
        for (int sb : on_edge[b]) {
          if (sa == sb) continue;
          const std::optional<PairHit> strict = TestPair(lines, sa, sb, options);
          const std::optional<PairHit> hit = TestPair(lines, sa, sb, loose);
          const double angle = std::acos(std::min(1.0, std::abs(lines[sa].n.dot(lines[sb].n)))) * 180 / M_PI;
          double ta = 0, tb = 0, error = -1;
          if (hit && hit->location) {
            ta = NearEndChange(lines[sa], *hit->location).t;
            tb = NearEndChange(lines[sb], *hit->location).t;
            error = (*hit->location - v.location).norm();
          }
          std::fprintf(csv, "%d,%s,%d,%.2f,%.2f,%d,%zu,%zu,%d,%d,%d,%.4f,%.2f,%.2f,%.2f,%.1f,%.1f,%.1f", id, tag.c_str(),
                       frame, v.location.x(), v.location.y(), crowded ? 1 : 0, a, b, sa, sb, strict ? 1 : 0,
                       hit ? hit->probability : 0.0, error, ta, tb, angle, lines[sa].length, lines[sb].length);
          for (const int seg : {sa, sb}) {
            int closest = -1;
            for (size_t j = 0; j < junctions.size(); ++j) {
              const bool uses = std::any_of(junctions[j].segments.begin(), junctions[j].segments.end(),
                                            [&](const JunctionSegment& js) { return js.line_segment == seg; });
              if (uses && (closest < 0 || (junctions[j].location - v.location).norm() <
                                              (junctions[closest].location - v.location).norm())) {
                closest = static_cast<int>(j);
              }
            }
            if (closest < 0) {
              std::fprintf(csv, ",-,-");
              continue;
            }
            std::fprintf(csv, ",%.2f,", (junctions[closest].location - v.location).norm());
            for (size_t k = 0; k < junctions[closest].segments.size(); ++k) {
              std::fprintf(csv, "%s%d", k ? "|" : "", junctions[closest].segments[k].line_segment);
            }
          }
          std::fprintf(csv, "\n");
        }
      }
    }
  }
  std::fclose(csv);
  LineSegments edges;
  for (const Eigen::Vector2d& far : v.long_edge_ends) {
    LineSegment edge;
    edge.p0 = v.location;
    edge.p1 = far;
    edges.push_back(edge);
  }
  char name[128];
  std::snprintf(name, sizeof name, "/notjoined_%04d_%s_%03d.png", id, tag.c_str(), frame);
  return WriteMissCrop(bench.miss_dir + name, v, any_truth, grey, segments, junctions, edges);
}

// Measures one generated sequence with each method.
// `clean_directory`: the same sequence rendered without noise (for the contrast-visible reading), or
// empty.
Status MeasureSequence(const JunctionBenchmarkOptions& bench, const std::string& directory, const std::string& clean_directory,
                       const std::vector<Method>& methods, const JunctionDetectorOptions& junction_options,
                       const std::string& overlay_prefix, std::vector<GeneratedStats>* stats) {
  Sequence sequence;
  SFM_RETURN_IF_ERROR(ReadSequence(directory, &sequence));
  GroundTruth truth;
  SFM_RETURN_IF_ERROR(ReadGroundTruth(directory, &truth));
  if (truth.frames.size() != sequence.frames.size()) {
    return Status::Error(directory + ": truth/frames has " + std::to_string(truth.frames.size()) +
                         " frames but images.txt " + std::to_string(sequence.frames.size()));
  }
  Sequence clean_sequence;
  if (!clean_directory.empty()) {
    SFM_RETURN_IF_ERROR(ReadSequence(clean_directory, &clean_sequence));
    if (clean_sequence.frames.size() != sequence.frames.size()) {
      return Status::Error(clean_directory + ": not the noise-free twin of " + directory);
    }
  }
  const Camera& camera = sequence.calibration.camera;
  const UndistortInterpolation interpolation = bench.undistort_interpolation;
  const ImageUndistorter undistorter(camera, interpolation);
  // Detection's view (--undistort_full_view): junctions in K's pixels, possibly outside the image.
  // The truth keeps its definition (--truth_in_image, the valid part of the undistorted image)
  // unless --truth_in_image=false, which with the full view counts the whole field of view.
  const UndistortView view = bench.undistort_view;
  const ImageUndistorter detection_undistorter(camera, interpolation, view);
  Eigen::Vector2d valid_offset = Eigen::Vector2d::Zero();
  cv::Size valid_size(camera.width, camera.height);
  if (view == UndistortView::kFullView && !bench.truth_in_image && camera.HasDistortion()) {
    FullViewCanvas(camera, 0, &valid_offset, &valid_size);
  }
  const cv::Mat valid = ValidMask(camera, bench.radius, bench.truth_in_image, valid_offset, valid_size);
  auto in_valid = [&](const Eigen::Vector2d& p) { return InMask(valid, p + valid_offset); };
  TrueJunctionOptions truth_options;
  truth_options.min_edge_px = bench.min_edge_px;
  if (bench.truth_in_stored_pixels) truth_options.stored_camera = &camera;
  // Where detections and truth are compared (the radius): undistorted, or stored pixels.
  auto compared = [&](std::vector<Eigen::Vector2d> points) {
    if (bench.truth_in_stored_pixels) {
      for (Eigen::Vector2d& p : points) p = camera.DistortPixel(p);
    }
    return points;
  };
  if (bench.truth_in_image) {
    truth_options.image_width = camera.width;
    truth_options.image_height = camera.height;
  }
  EndpointOffsetOptions offset_options;
  offset_options.max_abs_t = bench.max_abs_t;
  stats->assign(methods.size(), GeneratedStats());
  // Radial stretch of the undistortion in the middle of each ring (1 without distortion): how many
  // undistorted pixels one stored pixel becomes along the radius, d r_u / d r_d, measured along x.
  for (int k = 0; k < kNumRings; ++k) {
    const double r = k + 1 < kNumRings ? 0.5 * (kRingEdges[k] + kRingEdges[k + 1]) : 360.0;
    const Eigen::Vector2d p(camera.cx + r, camera.cy), q(camera.cx + r + 1, camera.cy);
    const double stretch = 1.0 / (camera.DistortPixel(q) - camera.DistortPixel(p)).norm();
    for (GeneratedStats& s : *stats) s.ring_stretch[k] = stretch;
  }

  for (size_t f = 0; f < sequence.frames.size(); ++f) {
    cv::Mat image;
    SFM_RETURN_IF_ERROR(LoadFrameImage(sequence, static_cast<int>(f), &image));
    const cv::Mat grey = undistorter.Apply(image);
    // True vertices count where the undistorted image shows them (with distortion, some of the
    // stored image's field of view falls outside the undistorted frame), radius px inside.
    // Contrast of every visible segment, measured in the undistorted noise-free twin.
    std::vector<double> contrast;
    cv::Mat clean_grey;
    if (!clean_directory.empty()) {
      cv::Mat clean;
      SFM_RETURN_IF_ERROR(LoadFrameImage(clean_sequence, static_cast<int>(f), &clean));
      clean_grey = undistorter.Apply(clean);
      contrast = EdgeContrasts(clean_grey, truth.frames[f], EdgeContrastOptions());
    }
    TrueJunctionOptions contrast_options = truth_options;
    if (!contrast.empty()) {
      contrast_options.segment_contrast = &contrast;
      contrast_options.min_contrast = bench.min_contrast_sigmas * bench.noise_sigma;
    }
    FrameTrueJunctions true_junctions = TrueJunctionsOfFrame(truth.wireframe, truth.frames[f], contrast_options);
    auto outside = [&](const TrueVertexJunction& v) { return !in_valid(v.location); };
    true_junctions.vertices.erase(
        std::remove_if(true_junctions.vertices.begin(), true_junctions.vertices.end(), outside),
        true_junctions.vertices.end());
    std::vector<Eigen::Vector2d> occlusions;
    for (const Eigen::Vector2d& p : true_junctions.occlusions) {
      if (in_valid(p)) occlusions.push_back(p);
    }
    const std::vector<TrueSegment> true_segments = TrueSegmentsOfFrame(truth.wireframe, truth.frames[f], truth_options);
    std::vector<Eigen::Vector2d> detectable, visible, any_truth;
    std::vector<int> detectable_type;
    std::vector<const TrueVertexJunction*> detectable_vertex;
    std::vector<bool> detectable_seen;  // contrast-visible
    for (const TrueVertexJunction& v : true_junctions.vertices) {
      visible.push_back(v.location);
      if (v.detectable) {
        detectable.push_back(v.location);
        detectable_vertex.push_back(&v);
        detectable_seen.push_back(v.contrast_detectable);
        detectable_type.push_back(static_cast<int>(v.type));
      }
    }
    // Every true image junction, whatever its edges' lengths: isolation and precision.
    TrueJunctionOptions every_options = truth_options;
    every_options.min_edge_px = 0;
    any_truth = visible;
    const FrameTrueJunctions every = TrueJunctionsOfFrame(truth.wireframe, truth.frames[f], every_options);
    any_truth.insert(any_truth.end(), every.occlusions.begin(), every.occlusions.end());
    TrueJunctionOptions long_options = truth_options;
    long_options.min_edge_px = 20;
    FrameTrueJunctions long_edged = TrueJunctionsOfFrame(truth.wireframe, truth.frames[f], long_options);
    long_edged.vertices.erase(std::remove_if(long_edged.vertices.begin(), long_edged.vertices.end(), outside),
                              long_edged.vertices.end());
    std::array<std::vector<Eigen::Vector2d>, kNumVariants> variant_points;
    for (const Eigen::Vector2d& p : detectable) {
      if (Isolated(bench, p, any_truth)) variant_points[0].push_back(p);
    }
    for (const TrueVertexJunction& v : long_edged.vertices) {
      if (!v.detectable) continue;
      variant_points[1].push_back(v.location);
      if (Isolated(bench, v.location, any_truth)) variant_points[2].push_back(v.location);
    }
    if (!contrast.empty()) {
      for (const TrueVertexJunction& v : true_junctions.vertices) {
        if (v.contrast_detectable) variant_points[3].push_back(v.location);
      }
      TrueJunctionOptions high_options = contrast_options;
      high_options.min_contrast = bench.edge_contrast_high;
      for (const TrueVertexJunction& v : TrueJunctionsOfFrame(truth.wireframe, truth.frames[f], high_options).vertices) {
        if (v.contrast_detectable && in_valid(v.location)) variant_points[4].push_back(v.location);
      }
    }

    for (size_t m = 0; m < methods.size(); ++m) {
      GeneratedStats& s = (*stats)[m];
      ++s.frames;
      s.has_contrast = s.has_contrast || !contrast.empty();
      auto start = Clock::now();
      LineSegments segments;
      Junctions junctions;
      if (detection_undistorter.SubViews().empty()) {
        segments = DetectUndistortedSegments(detection_undistorter, image, methods[m].options);
        s.segment_ms += Ms(start);
        // The junction step alone is short (under a millisecond); with --junction_repeats its time is
        // the fastest of that many runs on the same segments, which a loaded machine disturbs least.
        double fastest = 0;
        for (int r = 0; r < std::max(1, bench.junction_repeats); ++r) {
          start = Clock::now();
          junctions = DetectJunctions(segments, junction_options);
          const double ms = Ms(start);
          fastest = r == 0 ? ms : std::min(fastest, ms);
        }
        s.junction_ms += fastest;
      } else {
        // Sub-views: segments and junctions are found together, view by view; all in the segment time.
        junctions = DetectUndistortedJunctions(detection_undistorter, image, methods[m].options,
                                               junction_options, &segments);
        s.segment_ms += Ms(start);
      }
      s.segments += static_cast<int>(segments.size());
      const std::vector<Eigen::Vector2d> detected = Locations(junctions);

      // Recall over detectable vertices, with location error and type.
      s.detectable += static_cast<int>(detectable.size());
      std::vector<bool> detectable_found(detectable.size(), false);
      for (const PointMatch& match : MatchPoints(compared(detectable), compared(detected), bench.radius)) {
        ++s.detectable_found;
        detectable_found[match.truth] = true;
        s.errors.push_back(match.distance);
        ++s.found_by_type[detectable_type[match.truth]];
        ++s.confusion[detectable_type[match.truth]][static_cast<int>(junctions[match.detected].type)];
      }
      for (int type : detectable_type) ++s.true_by_type[type];
      for (size_t i = 0; i < detectable.size(); ++i) {
        const int ring = RingOf(camera, detectable[i]);
        ++s.ring_detectable[ring];
        if (detectable_found[i]) ++s.ring_found[ring];
        const int angle_ring = AngleRingOf(camera, detectable[i]);
        ++s.angle_detectable[angle_ring];
        if (detectable_found[i]) ++s.angle_found[angle_ring];
      }
      // The literal wording: a detected junction within the radius, shared or not.
      for (const Eigen::Vector2d& p : detectable) {
        if (std::any_of(detected.begin(), detected.end(),
                        [&](const Eigen::Vector2d& d) { return (d - p).norm() <= bench.radius; })) {
          ++s.detectable_near;
        }
      }
      for (size_t i = 0; i < detectable.size(); ++i) {
        if (detectable_found[i]) continue;
        const MissKind kind = WhyMissed(bench, *detectable_vertex[i], any_truth, segments, junction_options.max_gap_px);
        ++s.misses[kind];
        ++s.ring_misses[RingOf(camera, detectable[i])][kind];
        if (!contrast.empty() && detectable_seen[i]) ++s.contrast_misses[kind];
        const MissKind inner = WhySegmentsMissed(*detectable_vertex[i], segments, junction_options.max_gap_px);
        if (!bench.miss_dir.empty() && inner == kNotJoined) {
          SFM_RETURN_IF_ERROR(WriteNotJoined(bench, std::filesystem::path(directory).filename().string() + "_" + methods[m].name,
                                             static_cast<int>(f), *detectable_vertex[i], kind == kCrowded,
                                             any_truth, grey, segments, junctions, junction_options));
        }
        if (!bench.miss_dir.empty() && inner == kEdgesMissing) {
          SFM_RETURN_IF_ERROR(WriteMiss(bench, std::filesystem::path(directory).filename().string() + "_" + methods[m].name,
                                        static_cast<int>(f), *detectable_vertex[i], kind == kCrowded, any_truth, grey,
                                        clean_grey, segments, methods[m].options));
        }
        if (kind != kCrowded) continue;
        if (inner != kNotJoined) {
          ++s.crowded[inner == kEdgesMissing ? 0 : 1];
        } else {
          const bool near = std::any_of(detected.begin(), detected.end(), [&](const Eigen::Vector2d& d) {
            return (d - detectable[i]).norm() <= bench.radius;
          });
          ++s.crowded[near ? 2 : 3];
        }
      }
      for (int k = 0; k < kNumVariants; ++k) {
        s.variant_count[k] += static_cast<int>(variant_points[k].size());
        for (const PointMatch& match : MatchPoints(variant_points[k], detected, bench.radius)) {
          ++s.variant_found[k];
          s.variant_errors[k].push_back(match.distance);
        }
      }
      s.occlusions += static_cast<int>(occlusions.size());
      s.occlusions_found += static_cast<int>(MatchPoints(occlusions, detected, bench.radius).size());
      // Recall over every visible vertex junction, and which detections sit on a vertex.
      s.visible += static_cast<int>(visible.size());
      for (const PointMatch& match : MatchPoints(visible, detected, bench.radius)) {
        ++s.visible_found;
        ++s.detected_vertex_by_type[static_cast<int>(junctions[match.detected].type)];
      }
      // Precision: detections in the valid image part against vertices and occlusion T's.
      s.detected += static_cast<int>(junctions.size());
      for (const Junction& j : junctions) {
        ++s.detected_by_type[static_cast<int>(j.type)];
        if (in_valid(j.location)) ++s.detected_valid;
      }
      for (const PointMatch& match : MatchPoints(any_truth, detected, bench.radius)) {
        if (!in_valid(detected[match.detected])) continue;
        ++s.detected_correct;
        ++s.detected_correct_by_type[static_cast<int>(junctions[match.detected].type)];
      }
      // End-point offsets.
      for (const TrueSegment& t : true_segments) {
        for (int e = 0; e < 2; ++e) {
          if (!t.real_end[e]) continue;
          const bool use[2] = {e == 0, e == 1};
          CollectEndpointOffsets(segments, t.segment, use, offset_options,
                                 t.end[e] == SegmentEnd::kVertex ? &s.vertex_ends : &s.occlusion_ends);
        }
      }
      if (!overlay_prefix.empty() && f % 10 == 0) {
        std::vector<Eigen::Vector2d> missed;
        for (size_t i = 0; i < detectable.size(); ++i) {
          if (!detectable_found[i]) missed.push_back(detectable[i]);
        }
        const cv::Mat overlay = DrawJunctionOverlay(grey, segments, junctions, 2,
                                                    {{missed, {}, cv::Scalar(255, 255, 255), "missed vertices"}});
        char name[64];
        std::snprintf(name, sizeof name, "_%s_%06zu.png", methods[m].name.c_str(), f);
        SFM_RETURN_IF_ERROR(WritePng(overlay_prefix + name, overlay));
      }
    }
  }
  return Status::Ok();
}

// "count | found |" of the contrast-visible reading (variant 3), "- | - |" without a noise-free twin.
std::string ContrastCells(const GeneratedStats& s, bool bold) {
  if (!s.has_contrast) return "- | - | ";
  const std::string b = bold ? "**" : "";
  return std::to_string(s.variant_count[3]) + " | " + b + Percent(s.variant_found[3], s.variant_count[3]) + b + " | ";
}

// Measures the VGG Corridor images with each method, against the ground-truth junctions of each
// contact distance: (*stats)[method][contact].
Status MeasureVgg(const JunctionBenchmarkOptions& bench, const std::string& directory, const std::vector<Method>& methods, const std::vector<double>& contacts,
                  const JunctionDetectorOptions& junction_options, const std::string& overlay_dir,
                  std::vector<std::vector<VggStats>>* stats) {
  stats->assign(methods.size(), std::vector<VggStats>(contacts.size()));
  EndpointOffsetOptions offset_options;
  offset_options.max_abs_t = bench.max_abs_t;
  for (int i = 0;; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "bt.%03d", i);
    const std::string image_path = directory + "/" + stem + ".pgm";
    if (!std::filesystem::exists(image_path)) break;
    const cv::Mat grey = cv::imread(image_path, cv::IMREAD_GRAYSCALE);
    if (grey.empty()) return Status::Error(image_path + ": cannot decode as an image");
    LineSegments gt_segments;
    SFM_RETURN_IF_ERROR(ReadVggLines(directory + "/" + stem + ".lines", &gt_segments));
    std::vector<std::vector<SegmentJunction>> gt(contacts.size());
    std::vector<std::vector<Eigen::Vector2d>> gt_points(contacts.size());
    for (size_t c = 0; c < contacts.size(); ++c) {
      SegmentJunctionOptions gt_options;
      gt_options.contact_px = contacts[c];
      gt_options.min_angle_deg = bench.gt_min_angle_deg;
      gt[c] = JunctionsFromSegments(gt_segments, gt_options);
      for (const SegmentJunction& j : gt[c]) gt_points[c].push_back(j.location);
    }

    for (size_t m = 0; m < methods.size(); ++m) {
      const auto start = Clock::now();
      const LineSegments segments = DetectLineSegments(grey, methods[m].options);
      const double segment_ms = Ms(start);
      // As for the generated frames: the junction step's fastest of --junction_repeats runs.
      Junctions junctions;
      double junction_ms = 0;
      for (int r = 0; r < std::max(1, bench.junction_repeats); ++r) {
        const auto junction_start = Clock::now();
        junctions = DetectJunctions(segments, junction_options);
        const double run_ms = Ms(junction_start);
        junction_ms = r == 0 ? run_ms : std::min(junction_ms, run_ms);
      }
      if (bench.junction_repeats > 1) std::fprintf(stderr, "vgg junction_ms %.3f\n", junction_ms);
      const double ms = segment_ms + junction_ms;
      const std::vector<Eigen::Vector2d> detected = Locations(junctions);
      // Which detected segments lie on a GT segment (same line within 1.5 px, overlapping), and so
      // which junctions are made of at least two GT lines.
      std::vector<bool> on_gt(segments.size(), false);
      EndpointOffsetOptions same_line;
      same_line.max_line_distance = 1.5;
      same_line.min_true_length = 0;
      same_line.max_abs_t = 1e9;
      for (size_t k = 0; k < segments.size(); ++k) {
        for (const LineSegment& g : gt_segments) {
          EndpointOffsets probe;
          const bool one[2] = {true, false};
          CollectEndpointOffsets({g}, segments[k], one, same_line, &probe);
          if (!probe.t.empty()) {
            on_gt[k] = true;
            break;
          }
        }
      }
      std::vector<bool> junction_on_gt(junctions.size(), false);
      for (size_t k = 0; k < junctions.size(); ++k) {
        std::vector<int> lines;
        for (const JunctionSegment& js : junctions[k].segments) {
          if (js.line_segment >= 0 && on_gt[js.line_segment]) lines.push_back(js.line_segment);
        }
        std::sort(lines.begin(), lines.end());
        junction_on_gt[k] = std::unique(lines.begin(), lines.end()) - lines.begin() >= 2;
      }
      std::vector<bool> found;
      for (size_t c = 0; c < contacts.size(); ++c) {
        VggStats& s = (*stats)[m][c];
        ++s.images;
        s.ms += ms;
        s.gt_segments += static_cast<int>(gt_segments.size());
        s.gt_junctions += static_cast<int>(gt[c].size());
        s.detected += static_cast<int>(junctions.size());
        for (const SegmentJunction& j : gt[c]) ++s.gt_by_type[static_cast<int>(j.type)];
        auto near_border = [&](const Eigen::Vector2d& p) {
          return p.x() < bench.radius || p.y() < bench.radius || p.x() > grey.cols - 1 - bench.radius ||
                 p.y() > grey.rows - 1 - bench.radius;
        };
        for (size_t k = 0; k < junctions.size(); ++k) {
          ++s.detected_by_type[static_cast<int>(junctions[k].type)];
          if (near_border(junctions[k].location)) ++s.detected_border;
          if (junction_on_gt[k]) ++s.detected_on_gt;
        }
        found.assign(gt[c].size(), false);
        for (const PointMatch& match : MatchPoints(gt_points[c], detected, bench.radius)) {
          found[match.truth] = true;
          ++s.gt_found;
          ++s.detected_correct;
          if (near_border(detected[match.detected])) ++s.correct_border;
          if (junction_on_gt[match.detected]) ++s.correct_on_gt;
          ++s.gt_found_by_type[static_cast<int>(gt[c][match.truth].type)];
          ++s.detected_correct_by_type[static_cast<int>(junctions[match.detected].type)];
          s.errors.push_back(match.distance);
          s.dx.push_back(detected[match.detected].x() - gt_points[c][match.truth].x());
          s.dy.push_back(detected[match.detected].y() - gt_points[c][match.truth].y());
        }
        if (c != 0) continue;
        const bool both[2] = {true, true};
        for (const LineSegment& g : gt_segments) CollectEndpointOffsets(segments, g, both, offset_options, &s.ends);
        if (!overlay_dir.empty()) {
          std::vector<Eigen::Vector2d> missed;
          for (size_t k = 0; k < gt[c].size(); ++k) {
            if (!found[k]) missed.push_back(gt_points[c][k]);
          }
          const cv::Mat overlay =
              DrawJunctionOverlay(grey, segments, junctions, 2,
                                  {{{}, gt_segments, cv::Scalar(0, 140, 255), "GT segments"},
                                   {gt_points[c], {}, cv::Scalar(0, 255, 0), "GT junctions"},
                                   {missed, {}, cv::Scalar(255, 255, 255), "missed GT"}});
          SFM_RETURN_IF_ERROR(WritePng(overlay_dir + "/vgg_" + methods[m].name + "_" + stem + ".png", overlay));
        }
      }
    }
  }
  if (!stats->empty() && !(*stats)[0].empty() && (*stats)[0][0].images == 0) return Status::Error(directory + ": no bt.NNN.pgm images");
  return Status::Ok();
}

std::string EndpointRow(const std::string& source, const EndpointOffsets& o) {
  std::ostringstream row;
  const std::vector<double>& t = o.t;
  int positive = 0;
  double sum_positive = 0, sum_negative = 0;
  for (double v : t) {
    if (v >= 0) {
      ++positive;
      sum_positive += v;
    } else {
      sum_negative -= v;
    }
  }
  const int negative = static_cast<int>(t.size()) - positive;
  row << "| " << source << " | " << o.ends << " | " << o.unmatched << " | " << o.gross << " | " << t.size() << " | "
      << Fixed(Quantile(t, 0.5), 2) << " | " << Fixed(Quantile(t, 0.1), 2) << " / " << Fixed(Quantile(t, 0.9), 2)
      << " | " << Percent(positive, static_cast<int>(t.size())) << " | "
      << (positive ? Fixed(sum_positive / positive, 2) : "-") << " | "
      << (negative ? Fixed(sum_negative / negative, 2) : "-") << " | ";
  if (positive > 0 && negative > 0) {
    const EndpointModel model = FitEndpointModel(t);
    row << Fixed(model.lambda, 3) << " | " << Fixed(model.mu, 3) << " |";
  } else {
    row << "- | - |";
  }
  return row.str();
}

const char* kEndpointHeader =
    "| source | true ends | no detection | \\|t\\| > cap | samples | median t | 10 % / 90 % | t >= 0 | mean t (t >= 0) "
    "| mean -t (t < 0) | lambda (1/px) | mu (1/px) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";

}  // namespace

std::vector<std::string> SplitList(const std::string& text) { return Split(text); }

Status ParseSegmentMethods(const std::string& names, const SegmentDetectorOptions& base,
                           std::vector<JunctionBenchmarkMethod>* methods) {
  methods->clear();
  for (const std::string& name : Split(names)) {
    JunctionBenchmarkMethod method{name, base};
    if (const Status status = FromString(name, &method.options.method); !status.ok()) {
      return Status::Error("--segments: " + status.message());
    }
    methods->push_back(method);
  }
  if (methods->empty()) return Status::Error("--segments is empty");
  return Status::Ok();
}

Status ParseContactDistances(const std::string& text, std::vector<double>* contacts) {
  contacts->clear();
  for (const std::string& item : Split(text)) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !(value > 0 && value < 100)) {
      return Status::Error("--gt_contact_px lists distances in (0, 100) px, not '" + item + "'");
    }
    contacts->push_back(value);
  }
  if (contacts->empty()) return Status::Error("--gt_contact_px is empty");
  return Status::Ok();
}

std::vector<JunctionBenchmarkSequence> GivenSequences(const std::vector<std::string>& directories) {
  std::vector<JunctionBenchmarkSequence> sequences;
  for (const std::string& directory : directories) {
    const std::string clean = directory + "-noise-free";
    sequences.push_back({std::filesystem::path(directory).filename().string(), directory,
                         std::filesystem::exists(clean + "/images.txt") ? clean : ""});
  }
  return sequences;
}

Status GenerateStandardSequences(int frames, const std::string& work_dir,
                                 std::vector<JunctionBenchmarkSequence>* sequences) {
  sequences->clear();
  for (const auto& [name, options] : StandardSequences(frames)) {
    const std::string directory = work_dir + "/" + name;
    std::fprintf(stderr, "benchmark_junctions: generating %s\n", directory.c_str());
    SFM_RETURN_IF_ERROR(GenerateSequence(options, directory, true));
    GeneratorOptions clean_options = options;
    clean_options.render.noise_sigma = 0;
    SFM_RETURN_IF_ERROR(GenerateSequence(clean_options, directory + "-noise-free", true));
    sequences->push_back({name, directory, directory + "-noise-free"});
  }
  return Status::Ok();
}

Status JunctionBenchmarkReport(const JunctionBenchmarkOptions& bench,
                               const std::vector<JunctionBenchmarkSequence>& sequences,
                               const std::vector<JunctionBenchmarkMethod>& methods, const std::vector<double>& contacts,
                               const JunctionDetectorOptions& junction_options, std::string* text) {
  std::ostringstream report;
  report << "Junction options: lambda " << junction_options.endpoint_model.lambda << " /px, mu "
         << junction_options.endpoint_model.mu << " /px, min_probability " << junction_options.min_probability
         << ", max_gap_px " << junction_options.max_gap_px << ", collinear_tolerance_deg "
         << junction_options.collinear_tolerance_deg << ", collinear_max_offset_px "
         << junction_options.collinear_max_offset_px << ", min_arm_px " << junction_options.min_arm_px
         << ". Segment detectors at their defaults (min_length " << bench.min_segment_length << " px).\n\n";
  report << "## Generated sequences\n\n"
         << "Radius " << bench.radius << " px; detectable vertex: at least two visible edges of at least "
         << bench.min_edge_px << " px meet there, not just two collinear ones. True vertices and "
         << "detections count only inside the part of the undistorted image that the camera sees, at least "
         << bench.radius << " px from its border. Occlusion T: where a visible edge part of at least "
         << bench.min_edge_px << " px disappears behind a nearer face. Precision: detections matched to a visible "
         << "vertex junction or an occlusion T (of any length).\n\n"
         << "| sequence | segments | frames | detectable vertices | found within " << bench.radius
         << " px | any within " << bench.radius << " px (literal) | contrast-visible (step >= "
         << bench.min_contrast_sigmas << " sigma) | found | median error (px) | 90 % error (px) | all visible vertex junctions | found | occlusion T's | found "
         << "| detected | precision | segments/frame | ms/frame segments + junctions |\n"
         << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<GeneratedStats> pooled(methods.size());
  // Recall by distance from the principal point, and the reasons of the misses there.
  std::ostringstream rings;
  rings
      << "\n### Recall by distance from the principal point\n\n"
      << "Detectable vertices by their distance r from (cx, cy) in the undistorted image: found / count "
      << "(recall), then the misses as crowded / edges missing / ends far / not joined. \"stretch\": "
      << "d r_undistorted / d r_stored at the ring's middle (360 px for the last), 1 without distortion.\n\n"
      << "| sequence | segments |";
  for (int k = 0; k < kNumRings; ++k) {
    rings << " r " << kRingEdges[k] << (k + 1 < kNumRings ? "-" + Fixed(kRingEdges[k + 1], 0) : "+")
          << " px |";
  }
  rings << "\n|---|---|";
  for (int k = 0; k < kNumRings; ++k) rings << "---|";
  rings << "\n";
  std::ostringstream angles;
  angles << "\nBy angle from the optical axis (found / count, recall):\n\n| sequence | segments |";
  for (int k = 0; k < kNumAngleRings; ++k) {
    angles << " " << kAngleRingEdges[k] << "-" << kAngleRingEdges[k + 1] << " deg |";
  }
  angles << "\n|---|---|";
  for (int k = 0; k < kNumAngleRings; ++k) angles << "---|";
  angles << "\n";
  for (const auto& [name, directory, clean] : sequences) {
    std::fprintf(stderr, "benchmark_junctions: measuring %s\n", directory.c_str());
    std::vector<GeneratedStats> stats;
    const std::string prefix = bench.overlay_dir.empty() ? "" : bench.overlay_dir + "/" + name;
    if (const Status s = MeasureSequence(bench, directory, clean, methods, junction_options, prefix, &stats); !s.ok()) {
      return s;
    }
    for (size_t m = 0; m < methods.size(); ++m) pooled[m].Add(stats[m]);
    for (size_t m = 0; m < methods.size(); ++m) {
      const GeneratedStats& s = stats[m];
      rings << "| " << name << " | " << methods[m].name << " |";
      for (int k = 0; k < kNumRings; ++k) {
        rings << " " << s.ring_found[k] << " / " << s.ring_detectable[k] << " ("
              << Percent(s.ring_found[k], s.ring_detectable[k]) << "), miss " << s.ring_misses[k][kCrowded]
              << "/" << s.ring_misses[k][kEdgesMissing] << "/" << s.ring_misses[k][kEndsFar] << "/"
              << s.ring_misses[k][kNotJoined] << ", stretch " << Fixed(s.ring_stretch[k], 2) << " |";
      }
      rings << "\n";
      angles << "| " << name << " | " << methods[m].name << " |";
      for (int k = 0; k < kNumAngleRings; ++k) {
        angles << " " << s.angle_found[k] << " / " << s.angle_detectable[k] << " ("
               << Percent(s.angle_found[k], s.angle_detectable[k]) << ") |";
      }
      angles << "\n";
    }
    for (size_t m = 0; m < methods.size(); ++m) {
      const GeneratedStats& s = stats[m];
      report << "| " << name << " | " << methods[m].name << " | " << s.frames << " | " << s.detectable << " | "
             << Percent(s.detectable_found, s.detectable) << " | " << Percent(s.detectable_near, s.detectable) << " | "
             << ContrastCells(s, false)
             << Fixed(Quantile(s.errors, 0.5), 3) << " | "
             << Fixed(Quantile(s.errors, 0.9), 3) << " | " << s.visible << " | " << Percent(s.visible_found, s.visible)
             << " | " << s.occlusions << " | " << Percent(s.occlusions_found, s.occlusions) << " | " << s.detected << " | " << Percent(s.detected_correct, s.detected_valid) << " | "
             << Fixed(static_cast<double>(s.segments) / s.frames, 0) << " | "
             << Fixed(s.segment_ms / s.frames, 1) << " + " << Fixed(s.junction_ms / s.frames, 2) << " |\n";
    }
  }
  for (size_t m = 0; m < methods.size(); ++m) {
    const GeneratedStats& s = pooled[m];
    report << "| **all** | " << methods[m].name << " | " << s.frames << " | " << s.detectable << " | **"
           << Percent(s.detectable_found, s.detectable) << "** | " << Percent(s.detectable_near, s.detectable) << " | "
           << ContrastCells(s, true) << "**"
           << Fixed(Quantile(s.errors, 0.5), 3) << "** | "
           << Fixed(Quantile(s.errors, 0.9), 3) << " | " << s.visible << " | " << Percent(s.visible_found, s.visible)
           << " | " << s.occlusions << " | " << Percent(s.occlusions_found, s.occlusions) << " | " << s.detected << " | " << Percent(s.detected_correct, s.detected_valid) << " | "
           << Fixed(static_cast<double>(s.segments) / s.frames, 0) << " | " << Fixed(s.segment_ms / s.frames, 1)
           << " + " << Fixed(s.junction_ms / s.frames, 2) << " |\n";
  }

  report << rings.str() << angles.str();
  report << "\n### Other readings of \"detectable\", all generated frames\n\n"
         << "| vertices | segments | count | found | recall | median error (px) |\n|---|---|---|---|---|---|\n";
  for (size_t m = 0; m < methods.size(); ++m) {
    const GeneratedStats& s = pooled[m];
    report << "| every visible vertex junction | " << methods[m].name << " | " << s.visible << " | " << s.visible_found
           << " | " << Percent(s.visible_found, s.visible) << " | - |\n";
    report << "| main: at least two edges of at least " << bench.min_edge_px << " px | " << methods[m].name << " | "
           << s.detectable << " | " << s.detectable_found << " | " << Percent(s.detectable_found, s.detectable) << " | "
           << Fixed(Quantile(s.errors, 0.5), 3) << " |\n";
    for (int k = 0; k < kNumVariants; ++k) {
      report << "| " << VariantName(bench, k) << " | " << methods[m].name << " | " << s.variant_count[k] << " | "
             << s.variant_found[k] << " | " << Percent(s.variant_found[k], s.variant_count[k]) << " | "
             << Fixed(Quantile(s.variant_errors[k], 0.5), 3) << " |\n";
    }
  }
  report << "\n### Missed detectable vertices, all generated frames\n\n| reason |";
  for (const Method& method : methods) report << " " << method.name << " |";
  report << "\n|---|";
  for (size_t m = 0; m < methods.size(); ++m) report << "---|";
  report << "\n";
  for (int k = 0; k < kNumMissKinds; ++k) {
    report << "| " << kMissNames[k] << " |";
    for (size_t m = 0; m < methods.size(); ++m) {
      report << " " << pooled[m].misses[k] << " (" << Percent(pooled[m].misses[k], pooled[m].detectable) << " of all) |";
    }
    report << "\n";
  }
  for (int k = 0; k < kNumCrowdedKinds; ++k) {
    report << "| " << kCrowdedNames[k] << " |";
    for (size_t m = 0; m < methods.size(); ++m) {
      report << " " << pooled[m].crowded[k] << " (" << Percent(pooled[m].crowded[k], pooled[m].detectable) << " of all) |";
    }
    report << "\n";
  }
  if (pooled[0].has_contrast) {
    for (int k = 0; k < kNumMissKinds; ++k) {
      report << "| contrast-visible vertices only: " << kMissNames[k] << " |";
      for (size_t m = 0; m < methods.size(); ++m) {
        report << " " << pooled[m].contrast_misses[k] << " ("
               << Percent(pooled[m].contrast_misses[k], pooled[m].variant_count[3]) << " of contrast-visible) |";
      }
      report << "\n";
    }
  }
  for (size_t m = 0; m < methods.size(); ++m) {
    const GeneratedStats& s = pooled[m];
    report << "\n### Per type, all generated frames, " << methods[m].name << " segments\n\n"
           << "True type: of the detectable vertex (from its long edges). Detected type: of the detection. "
           << "\"on a vertex\": matched one-to-one to a visible vertex junction; \"correct\": to a vertex or "
           << "an occlusion T (valid image part).\n\n"
           << "| type | detectable vertices | found | recall | detected | on a vertex | correct | share correct |\n"
           << "|---|---|---|---|---|---|---|---|\n";
    for (int t = 0; t < kNumTypes; ++t) {
      report << "| " << JunctionTypeName(kTypes[t]) << " | " << s.true_by_type[t] << " | " << s.found_by_type[t]
             << " | " << Percent(s.found_by_type[t], s.true_by_type[t]) << " | " << s.detected_by_type[t] << " | "
             << s.detected_vertex_by_type[t] << " | " << s.detected_correct_by_type[t] << " | "
             << Percent(s.detected_correct_by_type[t], s.detected_by_type[t]) << " |\n";
    }
    report << "\nType of the found detectable vertices (rows: true, columns: detected):\n\n| true \\ detected |";
    for (JunctionType t : kTypes) report << " " << JunctionTypeName(t) << " |";
    report << " agree |\n|---|---|---|---|---|---|---|---|\n";
    for (int t = 0; t < kNumTypes; ++t) {
      report << "| " << JunctionTypeName(kTypes[t]) << " |";
      for (int d = 0; d < kNumTypes; ++d) report << " " << s.confusion[t][d] << " |";
      report << " " << Percent(s.confusion[t][t], s.found_by_type[t]) << " |\n";
    }
  }

  std::vector<std::vector<VggStats>> vgg;
  const bool have_vgg = std::filesystem::is_directory(bench.vgg_dir);
  if (have_vgg) {
    std::fprintf(stderr, "benchmark_junctions: measuring %s\n", bench.vgg_dir.c_str());
    if (const Status s = MeasureVgg(bench, bench.vgg_dir, methods, contacts, junction_options, bench.overlay_dir, &vgg);
        !s.ok()) {
      return s;
    }
    report << "\n## VGG Corridor\n\n"
           << "Ground-truth junctions: pairs of bt.NNN.lines segments at least " << bench.gt_min_angle_deg
           << " degrees from parallel whose line intersection lies within the contact distance of an end-point "
           << "of one and of the other segment (end or interior); pair points within " << kGtDefaults.merge_px
           << " px merged. Radius " << bench.radius << " px, one-to-one.\n\n"
           << "| segments | contact (px) | images | GT segments | GT junctions | found | recall | detected | precision "
           << "(lower bound) | precision away from the border | detections on two GT lines | their precision "
           << "| median error (px) | mean dx, dy (px) | ms/image |\n"
           << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (size_t m = 0; m < methods.size(); ++m) for (size_t c = 0; c < contacts.size(); ++c) {
      const VggStats& s = vgg[m][c];
      double mean_dx = 0, mean_dy = 0;
      for (double v : s.dx) mean_dx += v / std::max<size_t>(1, s.dx.size());
      for (double v : s.dy) mean_dy += v / std::max<size_t>(1, s.dy.size());
      report << "| " << methods[m].name << " | " << Fixed(contacts[c], 1) << " | " << s.images << " | " << s.gt_segments << " | " << s.gt_junctions
             << " | " << s.gt_found << " | **" << Percent(s.gt_found, s.gt_junctions) << "** | " << s.detected
             << " | **" << Percent(s.detected_correct, s.detected) << "** | "
             << Percent(s.detected_correct - s.correct_border, s.detected - s.detected_border) << " ("
             << s.detected_border << " within " << bench.radius << " px of the border left out) | " << s.detected_on_gt
             << " | " << Percent(s.correct_on_gt, s.detected_on_gt) << " | "
             << Fixed(Quantile(s.errors, 0.5), 3)
             << " | " << Fixed(mean_dx, 2) << ", " << Fixed(mean_dy, 2) << " | " << Fixed(s.ms / s.images, 1) << " |\n";
    }
    report << "\nGround-truth junctions of all images by contact distance:\n\n" << VggContactTable(bench, bench.vgg_dir);
    for (size_t m = 0; m < methods.size(); ++m) for (size_t c = 0; c < contacts.size(); ++c) {
      const VggStats& s = vgg[m][c];
      report << "\nPer type, " << methods[m].name << " segments, contact " << Fixed(contacts[c], 1) << " px:\n\n"
             << "| type | GT junctions | found | recall | detected | on a GT junction |\n|---|---|---|---|---|---|\n";
      for (int t = 0; t < kNumTypes; ++t) {
        report << "| " << JunctionTypeName(kTypes[t]) << " | " << s.gt_by_type[t] << " | " << s.gt_found_by_type[t]
               << " | " << Percent(s.gt_found_by_type[t], s.gt_by_type[t]) << " | " << s.detected_by_type[t] << " | "
               << s.detected_correct_by_type[t] << " |\n";
      }
    }
  } else {
    std::fprintf(stderr, "benchmark_junctions: %s not found; skipping VGG Corridor\n", bench.vgg_dir.c_str());
  }

  report << "\n## End-point model, eq. (5)\n\n"
         << "t = detected minus true end-point along the outward direction (eq. 8; t > 0: detected too long, "
         << "lambda's branch; t < 0: too short, mu's branch). Per true end, the detection on the same line "
         << "(both ends within " << kOffsetDefaults.max_line_distance << " px of it, within "
         << kOffsetDefaults.max_angle_deg << " degrees) overlapping the true segment that reaches farthest "
         << "towards the end; |t| > " << bench.max_abs_t << " px is counted apart. Maximum likelihood "
         << "(FitEndpointModel).\n\n";
  for (size_t m = 0; m < methods.size(); ++m) {
    report << "\n" << methods[m].name << " segments:\n\n" << kEndpointHeader;
    const GeneratedStats& s = pooled[m];
    EndpointOffsets all = s.vertex_ends;
    all.t.insert(all.t.end(), s.occlusion_ends.t.begin(), s.occlusion_ends.t.end());
    all.ends += s.occlusion_ends.ends;
    all.unmatched += s.occlusion_ends.unmatched;
    all.gross += s.occlusion_ends.gross;
    report << EndpointRow("generated, vertex ends", s.vertex_ends) << "\n"
           << EndpointRow("generated, occlusion ends", s.occlusion_ends) << "\n"
           << EndpointRow("generated, all", all) << "\n";
    if (have_vgg) report << EndpointRow("VGG GT segments", vgg[m][0].ends) << "\n";
  }

  *text = report.str();
  return Status::Ok();
}

}  // namespace sfm

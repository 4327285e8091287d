// The measurements and the report of benchmark_matching (matching_benchmark.h).
#include <glog/logging.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/epipolar.h"
#include "geometry/image_undistorter.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/junction_similarity.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "sequences/generator/ground_truth.h"
#include "pipeline/overlay/match_overlay.h"
#include "benchmarks/evaluation/matching_evaluation.h"
#include "benchmarks/evaluation/table_format.h"
#include "benchmarks/matching/matching_benchmark.h"

namespace sfm {
namespace {


std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

bool ParseNumbers(const std::string& text, std::vector<double>* values) {
  values->clear();
  for (const std::string& part : Split(text)) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (end == part.c_str() || *end != '\0' || !std::isfinite(v)) return false;
    values->push_back(v);
  }
  return !values->empty();
}

bool ParsePair(const std::string& text, int* a, int* b) {
  std::vector<double> v;
  if (!ParseNumbers(text, &v) || v.size() != 2 || v[0] < 0 || v[1] < 0 || v[0] != std::floor(v[0]) ||
      v[1] != std::floor(v[1]) || v[0] == v[1]) {
    return false;
  }
  *a = static_cast<int>(v[0]);
  *b = static_cast<int>(v[1]);
  return true;
}

std::string Goal(int part, int whole, double goal) {
  if (whole <= 0) return "-";
  return 100.0 * part / whole >= goal ? "pass (>= " + Fixed(goal, 0) + " %)" : "**miss** (< " + Fixed(goal, 0) + " %)";
}
double Median(std::vector<double> v) { return Quantile(std::move(v), 0.5); }

using Settings = MatchingBenchmarkSettings;

struct LoadedFrame {
  cv::Mat grey;  // undistorted
  FrameFeatures features;
  LbdFeatures lbd;
  // Set when the truth is given in the stored (distorted) image's pixels, as VGG's bt.NNN.P and
  // bt.NNN.lines are: the junctions (found on the undistorted image) are mapped back through this
  // camera's distortion before they are judged. Unset: the truth is in undistorted pixels
  // (generated sequences' truth/frames).
  std::optional<Camera> truth_in_distorted_pixels;
};

// A junction location in the pixels the frame's truth is given in.
Eigen::Vector2d JudgedPixel(const LoadedFrame& frame, const Eigen::Vector2d& undistorted) {
  return frame.truth_in_distorted_pixels ? frame.truth_in_distorted_pixels->DistortPixel(undistorted) : undistorted;
}

std::vector<Eigen::Vector2d> JudgedLocations(const LoadedFrame& frame) {
  std::vector<Eigen::Vector2d> locations = JunctionLocations(frame.features.junctions);
  for (Eigen::Vector2d& p : locations) p = JudgedPixel(frame, p);
  return locations;
}

Status LoadFrames(const MatchingBenchmarkOptions& bench, const Sequence& sequence, const Settings& settings, std::vector<LoadedFrame>* frames) {
  const ImageUndistorter undistorter(sequence.calibration.camera, settings.undistort_interpolation);
  frames->resize(sequence.frames.size());
  for (size_t f = 0; f < sequence.frames.size(); ++f) {
    cv::Mat image;
    SFM_RETURN_IF_ERROR(LoadFrameImage(sequence, static_cast<int>(f), &image));
    LoadedFrame& frame = (*frames)[f];
    frame.grey = undistorter.Apply(image).clone();
    frame.features = DetectFrameFeatures(frame.grey, settings.segments, settings.junctions);
    frame.lbd = DetectLbd(frame.grey, bench.lbd_min_length);
  }
  return Status::Ok();
}

Eigen::Matrix3d FundamentalOf(const Sequence& sequence, int i, int j, bool groundtruth) {
  const Frame& a = sequence.frames[i];
  const Frame& b = sequence.frames[j];
  return FundamentalFromOdometry(sequence.calibration.camera.K(), sequence.calibration.base_T_camera,
                                 groundtruth ? *a.world_T_base_groundtruth : a.world_T_base_odometry,
                                 groundtruth ? *b.world_T_base_groundtruth : b.world_T_base_odometry);
}

// What the matcher is given for a pair: F, and the relative pose with its uncertainty when it comes
// from poses and --match_pose (then MatchJunctions' PairGeometry overload is used).
struct PairInput {
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  std::optional<PairGeometry> geometry;
  operator const Eigen::Matrix3d&() const { return F; }
  const PairGeometry* Geometry() const { return geometry ? &*geometry : nullptr; }
};

PairInput PairInputOf(const MatchingBenchmarkOptions& bench, const Sequence& sequence, int i, int j, bool groundtruth) {
  PairInput input;
  input.F = FundamentalOf(sequence, i, j, groundtruth);
  if (bench.match_pose) {
    const Frame& a = sequence.frames[i];
    const Frame& b = sequence.frames[j];
    const OdometryNoise& noise = sequence.calibration.odometry_noise;
    // The sequence's noise model also with the true poses: the band is what the pipeline would use.
    input.geometry = PairGeometryFromOdometry(
        sequence.calibration.camera.K(), sequence.calibration.base_T_camera,
        groundtruth ? *a.world_T_base_groundtruth : a.world_T_base_odometry,
        groundtruth ? *b.world_T_base_groundtruth : b.world_T_base_odometry, noise.translation_sigma,
        noise.rotation_sigma, std::abs(j - i));
    input.F = input.geometry->Fundamental();
  }
  return input;
}

PairInput PairInputOf(const MatchingBenchmarkOptions& bench, const Eigen::Matrix3d& F) {
  PairInput input;
  input.F = F;
  return input;
}

std::vector<JunctionMatch> Match(const LoadedFrame& a, const LoadedFrame& b, const PairInput& input,
                                 const MatchingOptions& options, double* ms = nullptr,
                                 MatchingDiagnostics* diagnostics = nullptr) {
  const double start = ThreadCpuMs();
  std::vector<JunctionMatch> matches =
      input.geometry ? MatchJunctions(a.features.junctions, a.features.graph, b.features.junctions, b.features.graph,
                                      *input.geometry, options, diagnostics)
                     : MatchJunctions(a.features.junctions, a.features.graph, b.features.junctions, b.features.graph,
                                      input.F, options);
  if (ms) *ms = ThreadCpuMs() - start;
  return matches;
}

Status WritePng(const std::string& path, const cv::Mat& image) {
  std::vector<uchar> png;
  if (!cv::imencode(".png", image, png)) return Status::Error(path + ": PNG encoding failed");
  return WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

// ---- Data sets ---------------------------------------------------------------------------------

struct GeneratedData {
  std::string name;
  Sequence sequence;
  GroundTruth truth;
  std::vector<LoadedFrame> frames;
  std::vector<std::vector<std::vector<int>>> near_vertices;  // per frame, per junction: true vertices within the radius
  std::vector<std::vector<int>> lbd_line_id;  // per frame, per LSD segment: 3D line id or -1
};

Status LoadGenerated(const MatchingBenchmarkOptions& bench, const std::string& directory, const Settings& settings, GeneratedData* data) {
  data->name = std::filesystem::path(directory).filename().string();
  SFM_RETURN_IF_ERROR(ReadSequence(directory, &data->sequence));
  if (!data->sequence.has_groundtruth) return Status::Error(directory + ": no groundtruth.txt");
  SFM_RETURN_IF_ERROR(ReadGroundTruth(directory, &data->truth));
  if (data->truth.frames.size() != data->sequence.frames.size()) {
    return Status::Error(directory + ": truth/frames has " + std::to_string(data->truth.frames.size()) +
                         " frames but images.txt " + std::to_string(data->sequence.frames.size()));
  }
  SFM_RETURN_IF_ERROR(LoadFrames(bench, data->sequence, settings, &data->frames));
  const std::vector<int> edge_line = WireframeLineIds(data->truth.wireframe);
  for (size_t f = 0; f < data->frames.size(); ++f) {
    const FrameTruth& truth = data->truth.frames[f];
    data->near_vertices.push_back(TrueVerticesNearJunctions(data->frames[f].features.junctions, truth, bench.radius));
    LineSegments lines;
    std::vector<int> ids;
    TrueLinesOfFrame(truth, edge_line, &lines, &ids);
    std::vector<int> lbd_ids = AssociateSegments(data->frames[f].lbd.segments, lines, LineAssociationOptions());
    for (int& id : lbd_ids) {
      if (id >= 0) id = ids[id];
    }
    data->lbd_line_id.push_back(lbd_ids);
  }
  return Status::Ok();
}

struct VggData {
  Sequence sequence;
  VggTruth truth;
  std::vector<LoadedFrame> frames;
  std::vector<std::vector<int>> gt_junction_of;  // per frame, per junction: GT junction within radius, or -1
  std::vector<std::vector<std::vector<int>>> near_points;  // per frame, per junction: 3D points of corners within radius
  std::vector<std::vector<int>> lbd_line_id;     // per frame, per LSD segment: 3D line (bt.l3d row) or -1

  Eigen::Matrix3d TrueF(int i, int j) const { return FundamentalFromProjections(truth.views[i].P, truth.views[j].P); }
};

Status LoadVgg(const MatchingBenchmarkOptions& bench, const std::string& sequence_dir, const std::string& data_dir, const Settings& settings, VggData* data) {
  SFM_RETURN_IF_ERROR(ReadSequence(sequence_dir, &data->sequence));
  SFM_RETURN_IF_ERROR(ReadVggTruth(data_dir, SegmentJunctionOptions(), &data->truth));
  if (data->truth.views.size() != data->sequence.frames.size()) {
    return Status::Error(sequence_dir + ": " + std::to_string(data->sequence.frames.size()) + " frames but " +
                         data_dir + " has " + std::to_string(data->truth.views.size()) + " views");
  }
  SFM_RETURN_IF_ERROR(LoadFrames(bench, data->sequence, settings, &data->frames));
  for (LoadedFrame& frame : data->frames) {
    if (data->sequence.calibration.camera.HasDistortion()) frame.truth_in_distorted_pixels = data->sequence.calibration.camera;
  }
  for (size_t f = 0; f < data->frames.size(); ++f) {
    const VggView& view = data->truth.views[f];
    if (data->frames[f].grey.cols != 512 || data->frames[f].grey.rows != 512) {
      return Status::Error(sequence_dir + ": frame " + std::to_string(f) +
                           " is not 512x512: import without scaling so that pixels agree with bt.NNN.P");
    }
    std::vector<Eigen::Vector2d> gt_points;
    for (const SegmentJunction& j : view.junctions) gt_points.push_back(j.location);
    const std::vector<Eigen::Vector2d> locations = JudgedLocations(data->frames[f]);
    data->gt_junction_of.push_back(NearestWithin(locations, gt_points, bench.radius));
    data->near_points.push_back(VggPointsNear(view, locations, bench.radius));
    LineSegments lbd_judged = data->frames[f].lbd.segments;  // end-points in bt.NNN.lines' pixels
    for (LineSegment& s : lbd_judged) {
      s.p0 = JudgedPixel(data->frames[f], s.p0);
      s.p1 = JudgedPixel(data->frames[f], s.p1);
    }
    std::vector<int> ids = AssociateSegments(lbd_judged, view.lines, LineAssociationOptions());
    for (int& id : ids) {
      if (id >= 0) id = view.line3d[id];
    }
    data->lbd_line_id.push_back(ids);
  }
  return Status::Ok();
}

// The image line of a 3D line (a wireframe edge's line id; a bt.l3d row) in one frame.
LineOfId GeneratedLineOf(const GeneratedData& d, int frame) {
  const Eigen::Matrix<double, 3, 4> P =
      d.sequence.calibration.camera.K() * d.truth.frames.at(frame).world_T_camera.Inverse().Matrix3x4();
  return [&d, P](int id) {
    const WireEdge& e = d.truth.wireframe.edges.at(id);
    return ProjectLine(P, d.truth.wireframe.vertices[e.vertex_a], d.truth.wireframe.vertices[e.vertex_b]);
  };
}
LineOfId VggLineOf(const VggData& d, int frame) {
  const Eigen::Matrix<double, 3, 4> P = d.truth.views.at(frame).P;
  return [&d, P](int id) { return ProjectLine(P, d.truth.lines3d.at(id).first, d.truth.lines3d.at(id).second); };
}

SameFeature GeneratedSame(const std::vector<std::vector<int>>& near_a, const std::vector<std::vector<int>>& near_b) {
  return [&near_a, &near_b](int ia, int ib) { return SameTrueVertex(near_a.at(ia), near_b.at(ib)); };
}

// Identity from the reconstructed corners (3D points) and from the GT junctions with 3D lines:
// different if either says so, the same if either says so, else unknown.
SameFeature VggSame(const VggData& d, int i, int j) {
  return [&d, i, j](int ia, int ib) {
    const int by_points = SameTrueVertex(d.near_points[i].at(ia), d.near_points[j].at(ib));
    const int ga = d.gt_junction_of[i].at(ia), gb = d.gt_junction_of[j].at(ib);
    const int by_lines = ga < 0 || gb < 0 ? -1 : SameVggJunction(d.truth.views[i], ga, d.truth.views[j], gb);
    if (by_points == 0 || by_lines == 0) return 0;
    return std::max(by_points, by_lines);
  };
}

// The same data with the junctions `drop` says dropped (topology graphs rebuilt), for diagnosis.
template <typename Drop>
VggData WithoutJunctions(const VggData& data, Drop drop) {
  VggData out = data;
  for (size_t f = 0; f < out.frames.size(); ++f) {
    FrameFeatures& features = out.frames[f].features;
    Junctions kept;
    std::vector<int> gt;
    std::vector<std::vector<int>> points;
    for (size_t k = 0; k < features.junctions.size(); ++k) {
      if (drop(out.frames[f].grey, features.junctions[k])) continue;
      kept.push_back(features.junctions[k]);
      gt.push_back(data.gt_junction_of[f][k]);
      points.push_back(data.near_points[f][k]);
    }
    features.junctions = kept;
    features.graph = BuildTopologyGraph(kept);
    out.gt_junction_of[f] = gt;
    out.near_points[f] = points;
  }
  return out;
}

// The frames with only their n highest-scoring junctions (ties: lower index), graphs rebuilt.
std::vector<LoadedFrame> StrongestJunctions(const std::vector<LoadedFrame>& frames, int n) {
  std::vector<LoadedFrame> out = frames;
  for (LoadedFrame& frame : out) {
    Junctions& junctions = frame.features.junctions;
    std::vector<int> order(junctions.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return junctions[x].score > junctions[y].score; });
    order.resize(std::min<size_t>(order.size(), n));
    std::sort(order.begin(), order.end());
    Junctions kept;
    for (int k : order) kept.push_back(junctions[k]);
    junctions = kept;
    frame.features.graph = BuildTopologyGraph(kept);
  }
  return out;
}

// Distances of true vertices seen in both frames from each other's epipolar lines under F (the
// larger of the two), px: how far F is from the truth where it matters.
void TrueVertexEpipolarErrors(const FrameTruth& a, const FrameTruth& b, const Eigen::Matrix3d& F,
                              std::vector<double>* errors) {
  std::map<int, Eigen::Vector2d> in_b;
  for (const VisibleVertex& v : b.vertices) in_b[v.vertex] = v.pixel;
  for (const VisibleVertex& v : a.vertices) {
    const auto it = in_b.find(v.vertex);
    if (it == in_b.end()) continue;
    errors->push_back(std::max(PointLineDistance(EpipolarLineInImage2(F, v.pixel), it->second),
                               PointLineDistance(EpipolarLineInImage1(F, it->second), v.pixel)));
  }
}

// ---- Geometric verification (f) ------------------------------------------------------------------

// One pair's refinement, set beside the truth: is a fallback the estimate's fault (caught by wrong
// matches) or the prior's (the odometry further from the truth than its covariance says)? The same
// refinement is also run on the pair's true correspondences (corner tracks), which have no wrong
// matches: if it too leaves the prior's ellipsoid, the matches are not the cause.
struct RefinementCase {
  std::string pair;
  PairRefinement::Outcome outcome = PairRefinement::Outcome::kTooFewMatches;
  double estimate_distance = 0;  // squared Mahalanobis distance from the odometry, estimate
  double truth_distance = 0;     // the same for the true pose
  double true_match_distance = 0;  // the estimate from the true correspondences
  double rotation_odometry = 0, rotation_estimate = 0, rotation_true_matches = 0;  // deg from the truth
  double direction_odometry = 0, direction_estimate = 0, direction_true_matches = 0;  // deg, translation
  double epipolar_odometry = 0, epipolar_truth = 0, epipolar_estimate = 0, epipolar_true_matches = 0;  // px, median
  int true_matches = 0;
};

const char* OutcomeName(PairRefinement::Outcome outcome) {
  switch (outcome) {
    case PairRefinement::Outcome::kRefined: return "refined";
    case PairRefinement::Outcome::kNoPriorUncertainty: return "no prior variance";
    case PairRefinement::Outcome::kTooFewMatches: return "too few matches";
    case PairRefinement::Outcome::kTooFewInliers: return "too few inliers";
    case PairRefinement::Outcome::kInconsistentWithPrior: return "outside the prior";
  }
  return "?";
}


// What the refinement did on a set of pairs, and how far the pose it used is from the truth.
struct RefinementTally {
  int pairs = 0;
  int outcomes[5] = {};  // by PairRefinement::Outcome
  std::vector<double> first_matches, inliers, steps, prior_distance;
  std::vector<double> rotation_before, rotation_after;    // degrees, odometry / the pose used
  std::vector<double> direction_before, direction_after;  // angle of the translation, degrees
  std::vector<double> epipolar_before, epipolar_after;    // px, true correspondences under each F

  // true_errors(F, errors) appends the epipolar errors of the pair's true correspondences under F.
  template <typename TrueErrors>
  void Add(const MatchingDiagnostics& d, const PairGeometry& odometry_geometry, const Pose3& truth,
           TrueErrors true_errors) {
    const Pose3& odometry = odometry_geometry.camera2_T_camera1;
    true_errors(odometry_geometry.Fundamental(), &epipolar_before);
    true_errors(d.refinement.Refined() ? d.refinement.geometry.Fundamental() : odometry_geometry.Fundamental(),
                &epipolar_after);
    ++pairs;
    ++outcomes[static_cast<int>(d.refinement.outcome)];
    first_matches.push_back(d.first_pass_matches);
    if (d.refinement.outcome != PairRefinement::Outcome::kTooFewMatches &&
        d.refinement.outcome != PairRefinement::Outcome::kNoPriorUncertainty) {
      prior_distance.push_back(d.refinement.prior_distance_squared);
    }
    const Pose3& used = d.refinement.Refined() ? d.refinement.geometry.camera2_T_camera1 : odometry;
    if (d.refinement.Refined()) {
      inliers.push_back(d.refinement.inliers);
      steps.push_back(d.refinement.iterations);
    }
    constexpr double kDegrees = 180 / 3.14159265358979323846;
    auto direction = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
      return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0));
    };
    rotation_before.push_back(kDegrees * RotationAngle(odometry.rotation, truth.rotation));
    rotation_after.push_back(kDegrees * RotationAngle(used.rotation, truth.rotation));
    direction_before.push_back(kDegrees * direction(odometry.translation, truth.translation));
    direction_after.push_back(kDegrees * direction(used.translation, truth.translation));
  }
};

std::string RefinementRow(const std::string& data, const RefinementTally& t) {
  using Outcome = PairRefinement::Outcome;
  auto spread = [](const std::vector<double>& before, const std::vector<double>& after) {
    return Fixed(Median(before), 3) + " / " + Fixed(Quantile(before, 0.9), 3) + " -> **" + Fixed(Median(after), 3) +
           "** / " + Fixed(Quantile(after, 0.9), 3);
  };
  std::ostringstream row;
  row << "| " << data << " | " << t.pairs << " | " << t.outcomes[static_cast<int>(Outcome::kRefined)] << " | "
      << t.outcomes[static_cast<int>(Outcome::kTooFewMatches)] << " | "
      << t.outcomes[static_cast<int>(Outcome::kTooFewInliers)] << " | "
      << t.outcomes[static_cast<int>(Outcome::kInconsistentWithPrior)] << " | " << Fixed(Median(t.first_matches), 0)
      << " | " << (t.inliers.empty() ? "-" : Fixed(Median(t.inliers), 0)) << " | "
      << (t.steps.empty() ? "-" : Fixed(Median(t.steps), 0)) << " | "
      << (t.prior_distance.empty() ? "-"
                                   : Fixed(Median(t.prior_distance), 1) + " / " + Fixed(Quantile(t.prior_distance, 1.0), 1))
      << " | " << spread(t.rotation_before, t.rotation_after)
      << " | " << spread(t.direction_before, t.direction_after) << " | "
      << spread(t.epipolar_before, t.epipolar_after) << " |\n";
  return row.str();
}

// The same for the VGG corners that bt.nview-corners identifies as one 3D point in both views.
// F acts on undistorted pixels (the matcher's); the data set's corners are in the stored image's,
// so they are undistorted with the sequence's camera first.
void VggCornerEpipolarErrors(const VggView& a, const VggView& b, const Camera& camera, const Eigen::Matrix3d& F,
                             std::vector<double>* errors) {
  std::map<int, Eigen::Vector2d> in_b;
  for (size_t k = 0; k < b.corners.size(); ++k) {
    if (b.corner_point3d[k] >= 0) in_b[b.corner_point3d[k]] = camera.UndistortPixel(b.corners[k]);
  }
  for (size_t k = 0; k < a.corners.size(); ++k) {
    const auto it = in_b.find(a.corner_point3d[k]);
    if (a.corner_point3d[k] < 0 || it == in_b.end()) continue;
    const Eigen::Vector2d corner = camera.UndistortPixel(a.corners[k]);
    errors->push_back(std::max(PointLineDistance(EpipolarLineInImage2(F, corner), it->second),
                               PointLineDistance(EpipolarLineInImage1(F, it->second), corner)));
  }
}

RefinementCase VggRefinementCase(const MatchingBenchmarkOptions& bench, const VggData& d, int i, int j, const PairGeometry& odometry,
                                 const PairRefinement& refinement, const MatchingOptions& matching) {
  constexpr double kDegrees = 180 / 3.14159265358979323846;
  const Pose3 truth = PairInputOf(bench, d.sequence, i, j, true).geometry->camera2_T_camera1;
  auto median_error = [&](const Eigen::Matrix3d& F) {
    std::vector<double> errors;
    VggCornerEpipolarErrors(d.truth.views[i], d.truth.views[j], d.sequence.calibration.camera, F, &errors);
    return Median(errors);
  };
  auto fundamental = [&](const Pose3& pose) {
    PairGeometry g = odometry;
    g.camera2_T_camera1 = pose;
    return g.Fundamental();
  };
  RefinementCase c;
  c.pair = std::to_string(i) + "-" + std::to_string(j);
  c.outcome = refinement.outcome;
  c.estimate_distance = refinement.prior_distance_squared;
  c.truth_distance = PriorDistanceSquared(odometry, truth);
  c.rotation_odometry = kDegrees * RotationAngle(odometry.camera2_T_camera1.rotation, truth.rotation);
  c.rotation_estimate = kDegrees * RotationAngle(refinement.estimate.rotation, truth.rotation);
  auto direction = [&](const Pose3& pose) {
    return kDegrees * std::acos(std::clamp(pose.translation.normalized().dot(truth.translation.normalized()), -1.0, 1.0));
  };
  c.direction_odometry = direction(odometry.camera2_T_camera1);
  c.direction_estimate = direction(refinement.estimate);
  c.epipolar_odometry = median_error(odometry.Fundamental());
  c.epipolar_truth = median_error(fundamental(truth));
  c.epipolar_estimate = median_error(fundamental(refinement.estimate));
  // The true correspondences: corners of one bt.p3d point in both views.
  std::map<int, Eigen::Vector2d> in_j;
  const VggView& a = d.truth.views[i];
  const VggView& b = d.truth.views[j];
  for (size_t k = 0; k < b.corners.size(); ++k) {
    if (b.corner_point3d[k] >= 0) in_j[b.corner_point3d[k]] = b.corners[k];
  }
  std::vector<Eigen::Vector2d> x1, x2;
  for (size_t k = 0; k < a.corners.size(); ++k) {
    const auto it = in_j.find(a.corner_point3d[k]);
    if (a.corner_point3d[k] < 0 || it == in_j.end()) continue;
    x1.push_back(a.corners[k]);
    x2.push_back(it->second);
  }
  PairRefinementSettings settings;
  settings.location_sigma_px = matching.location_sigma_px;
  settings.gate_sigmas = matching.refine_gate_sigmas;
  settings.min_inliers = matching.refine_min_inliers;
  const PairRefinement from_truth = RefinePairGeometry(odometry, x1, x2, settings);
  c.true_matches = static_cast<int>(x1.size());
  c.true_match_distance = from_truth.prior_distance_squared;
  c.rotation_true_matches = kDegrees * RotationAngle(from_truth.estimate.rotation, truth.rotation);
  c.direction_true_matches = direction(from_truth.estimate);
  c.epipolar_true_matches = median_error(fundamental(from_truth.estimate));
  return c;
}

// ---- Comparison with LSD + LBD (d) --------------------------------------------------------------

struct MethodStats {
  int pairs = 0;
  double features = 0;  // per frame, summed over both frames of every pair
  MatchVerdicts verdicts;
  FeatureRecall recall;
  std::vector<double> detect_ms, match_ms;  // per pair
};

std::string MethodRow(const std::string& data, const std::string& method, const MethodStats& s) {
  std::ostringstream row;
  const double pairs = std::max(1, s.pairs);
  row << "| " << data << " | " << method << " | " << s.pairs << " | " << Fixed(s.features / (2 * pairs), 0) << " | "
      << Fixed(s.verdicts.matches / pairs, 1) << " | " << s.verdicts.correct << " / " << s.verdicts.matches << " = **"
      << Percent(s.verdicts.correct, s.verdicts.matches) << "** | " << Percent(s.verdicts.identity_known, s.verdicts.matches)
      << " | " << Percent(s.verdicts.correct_known, s.verdicts.identity_known) << " | " << s.recall.matched << " / " << s.recall.seen_both << " = **" << Percent(s.recall.matched, s.recall.seen_both)
      << "** | " << Fixed(Median(s.detect_ms), 1) << " | " << Fixed(Median(s.match_ms), 2) << " | "
      << Fixed(Median(s.detect_ms) + Median(s.match_ms), 1) << " |\n";
  return row.str();
}

// One pair for LBD: nearest-neighbour and mutual matches, judged; appended to the two stats.
void AddLbdPair(const MatchingBenchmarkOptions& bench, const LoadedFrame& a, const LoadedFrame& b, const std::vector<int>& id_a, const std::vector<int>& id_b,
                const LineOfId& line_in_a, const LineOfId& line_in_b, const Eigen::Matrix3d& F_true,
                MethodStats* nearest, MethodStats* mutual) {
  for (auto [stats, is_mutual] : {std::pair{nearest, false}, std::pair{mutual, true}}) {
    const double start = ThreadCpuMs();
    const std::vector<std::pair<int, int>> matches = MatchLbd(a.lbd.descriptors, b.lbd.descriptors, is_mutual);
    stats->match_ms.push_back(ThreadCpuMs() - start);
    stats->detect_ms.push_back(a.lbd.detect_ms + b.lbd.detect_ms);
    ++stats->pairs;
    stats->features += a.lbd.segments.size() + b.lbd.segments.size();
    const LineMatchScore score =
        ScoreLineMatches(a.lbd.segments, b.lbd.segments, matches, id_a, id_b, line_in_a, line_in_b, F_true,
                         bench.epipolar_tolerance);
    stats->verdicts.Add(score.verdicts);
    stats->recall.Add({score.seen_both, score.matched});
  }
}

// ---- Table 2 (c) -------------------------------------------------------------------------------

struct SweepCell {
  MatchVerdicts rho, sigma;
};

struct Sweep {
  std::vector<double> R, tau2;
  std::vector<std::vector<SweepCell>> cells;  // [R][tau2]
};

Sweep RunSweep(const MatchingBenchmarkOptions& bench, const LoadedFrame& a, const LoadedFrame& b, const PairInput& F, const Eigen::Matrix3d& F_true,
               const SameFeature& same, const MatchingOptions& base, const std::vector<double>& R_values,
               const std::vector<double>& tau2_values) {
  Sweep sweep{R_values, tau2_values, {}};
  const std::vector<Eigen::Vector2d> pa = JudgedLocations(a), pb = JudgedLocations(b);
  for (double R : R_values) {
    sweep.cells.emplace_back();
    for (double tau2 : tau2_values) {
      SweepCell cell;
      for (bool topology : {false, true}) {
        MatchingOptions options = base;
        options.max_epipolar_distance_px = R;
        options.use_pose_band = false;    // the sweep is over R
        options.refine_geometry = false;  // the guided pass would replace R by the refined band
        options.tau2 = tau2;
        options.use_topology = topology;
        const std::vector<JunctionMatch> matches = Match(a, b, F, options);
        (topology ? cell.sigma : cell.rho) =
            JudgeMatches(MatchPairs(matches), pa, pb, F_true, bench.epipolar_tolerance, same);
      }
      sweep.cells.back().push_back(cell);
    }
  }
  return sweep;
}

std::string SweepTable(const Sweep& s) {
  std::ostringstream t;
  t << "| R (px) | tau2 | rho: matches | correct | mismatches | sigma: matches | correct | mismatches |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  for (size_t r = 0; r < s.R.size(); ++r) {
    for (size_t k = 0; k < s.tau2.size(); ++k) {
      const SweepCell& c = s.cells[r][k];
      t << "| " << Fixed(s.R[r], 0) << " | " << Fixed(s.tau2[k], 2) << " | " << c.rho.matches << " | " << c.rho.correct
        << " | " << c.rho.Wrong() << " | " << c.sigma.matches << " | " << c.sigma.correct << " | " << c.sigma.Wrong()
        << " |\n";
    }
  }
  // Summary: what each measure keeps from the smallest tau2 to the largest, and its mismatch rate.
  int rho_first = 0, rho_last = 0, sigma_first = 0, sigma_last = 0, rho_all = 0, rho_wrong = 0, sigma_all = 0,
      sigma_wrong = 0;
  for (size_t r = 0; r < s.R.size(); ++r) {
    rho_first += s.cells[r].front().rho.correct;
    rho_last += s.cells[r].back().rho.correct;
    sigma_first += s.cells[r].front().sigma.correct;
    sigma_last += s.cells[r].back().sigma.correct;
    for (const SweepCell& c : s.cells[r]) {
      rho_all += c.rho.matches;
      rho_wrong += c.rho.Wrong();
      sigma_all += c.sigma.matches;
      sigma_wrong += c.sigma.Wrong();
    }
  }
  t << "\nSummed over R: correct matches at tau2 = " << Fixed(s.tau2.front(), 2) << " -> " << Fixed(s.tau2.back(), 2)
    << ": rho " << rho_first << " -> " << rho_last << " (keeps " << Percent(rho_last, rho_first) << "), sigma "
    << sigma_first << " -> " << sigma_last << " (keeps " << Percent(sigma_last, sigma_first)
    << "). Mismatches over the whole grid: rho " << rho_wrong << " of " << rho_all << " (" << Percent(rho_wrong, rho_all)
    << "), sigma " << sigma_wrong << " of " << sigma_all << " (" << Percent(sigma_wrong, sigma_all) << ").\n";
  return t.str();
}

// A Fig. 6-style picture with each match's verdict.
Status WriteVerdictPicture(const MatchingBenchmarkOptions& bench, const std::string& path, const LoadedFrame& a, const LoadedFrame& b,
                           const std::vector<JunctionMatch>& matches, const Eigen::Matrix3d& F_true,
                           const SameFeature& same) {
  std::vector<bool> correct;
  const std::vector<Eigen::Vector2d> judged_a = JudgedLocations(a), judged_b = JudgedLocations(b);
  // Partial matches included: DrawMatchOverlay pairs their segments by PartnerSegment and draws the
  // left-out one in grey.
  for (const JunctionMatch& m : matches) {
    const MatchVerdicts v =
        JudgeMatches({{m.index_a, m.index_b}}, judged_a, judged_b, F_true, bench.epipolar_tolerance, same);
    correct.push_back(v.correct == 1);
  }
  return WritePng(path, DrawMatchOverlay(a.grey, a.features.junctions, b.grey, b.features.junctions, matches,
                                         2, correct));
}


// Wrong matches by junction type (in image 1), and how far they are from the true epipolar geometry.
struct WrongTally {
  int matches = 0, wrong = 0;
  int by_type[6] = {}, matches_by_type[6] = {};
  int epipolar_ok = 0;  // wrong, yet within the tolerance of the true epipolar lines (along them)
  int at_border = 0;    // wrong, with a junction within 5 px of the image border
};

// Counts the wrong matches: with identity_only, those ground truth identifies as two different
// features; else those JudgeMatches does not call correct.
void TallyWrong(const MatchingBenchmarkOptions& bench, const LoadedFrame& a, const LoadedFrame& b, const std::vector<JunctionMatch>& matches,
                const Eigen::Matrix3d& F_true, const SameFeature& same, bool identity_only, WrongTally* tally) {
  auto near_border = [](const cv::Mat& image, const Eigen::Vector2d& p) {
    return p.x() < 5 || p.y() < 5 || p.x() > image.cols - 6 || p.y() > image.rows - 6;
  };
  for (const JunctionMatch& m : matches) {
    const Junction& ja = a.features.junctions[m.index_a];
    const Junction& jb = b.features.junctions[m.index_b];
    const int type = static_cast<int>(ja.type);
    const int identity = same(m.index_a, m.index_b);
    const bool epipolar_ok = EpipolarConsistent(F_true, JudgedPixel(a, ja.location), JudgedPixel(b, jb.location),
                                                bench.epipolar_tolerance);
    if (identity_only && identity < 0) continue;
    ++tally->matches;
    ++tally->matches_by_type[type];
    const bool wrong = identity_only ? identity == 0 : (!epipolar_ok || identity == 0);
    if (!wrong) continue;
    ++tally->wrong;
    ++tally->by_type[type];
    if (epipolar_ok) ++tally->epipolar_ok;
    if (near_border(a.grey, ja.location) || near_border(b.grey, jb.location)) ++tally->at_border;
  }
}

std::string WrongTable(const MatchingBenchmarkOptions& bench, const WrongTally& t) {
  std::ostringstream table;
  table << "| | L | Y | ARROW | T | X | N | all | within " << bench.epipolar_tolerance
        << " px of the true epipolar lines | within 5 px of the border |\n|---|---|---|---|---|---|---|---|---|---|\n"
        << "| matches |";
  for (int k = 0; k < 6; ++k) table << " " << t.matches_by_type[k] << " |";
  table << " " << t.matches << " | | |\n| wrong |";
  for (int k = 0; k < 6; ++k) table << " " << t.by_type[k] << " (" << Percent(t.by_type[k], t.matches_by_type[k]) << ") |";
  table << " " << t.wrong << " (" << Percent(t.wrong, t.matches) << ") | " << t.epipolar_ok << " | " << t.at_border
        << " |\n";
  return table.str();
}

// One CSV row per match of a VGG pair, for the analysis of the wrong ones: the verdict, the two
// junctions, their distances from the true and from the used epipolar lines, the band of the pass
// that made the match, rho and sigma, and where the true partner of junction a was.
void AppendVggMatchRows(const MatchingBenchmarkOptions& bench, const VggData& d, int i, int j, const PairInput& input,
                        const MatchingOptions& options, const std::vector<JunctionMatch>& matches,
                        const MatchingDiagnostics& diagnostics, std::string* csv) {
  const Junctions& a = d.frames[i].features.junctions;
  const Junctions& b = d.frames[j].features.junctions;
  const Eigen::Matrix3d F_true = d.TrueF(i, j);
  const bool refined = diagnostics.refinement.Refined();
  const PairGeometry used = refined ? diagnostics.refinement.geometry : *input.geometry;
  MatchingOptions pass = options;
  if (refined) {
    pass.use_pose_band = true;
    pass.band_sigmas = options.refine_gate_sigmas;
  }
  const JunctionSimilarity similarity(a, b, used, pass);
  const Eigen::Matrix3d F_used = used.Fundamental();
  MatchingOptions first_only = options;
  first_only.refine_geometry = false;
  const std::vector<JunctionMatch> first = MatchJunctions(
      a, d.frames[i].features.graph, b, d.frames[j].features.graph, *input.geometry, first_only);
  std::set<std::pair<int, int>> in_first;
  for (const JunctionMatch& m : first) in_first.insert({m.index_a, m.index_b});
  std::vector<int> partner_of_b(b.size(), -1);
  for (const JunctionMatch& m : matches) partner_of_b[m.index_b] = m.index_a;
  const SameFeature same = VggSame(d, i, j);
  const TopologyGraph& graph_b = d.frames[j].features.graph;
  auto neighbours = [&graph_b](int x, int y) {
    for (const int e : graph_b.edges_of_junction[x]) {
      const TopologyEdge& edge = graph_b.edges[e];
      if (edge.junction_a == y || edge.junction_b == y) return true;
    }
    return false;
  };
  auto lengths = [](const Junction& junction) {
    std::string text;
    for (const JunctionSegment& s : junction.segments) {
      text += (text.empty() ? "" : ";") + Fixed((s.end - junction.location).norm(), 1);
    }
    return text;
  };
  std::ostringstream out;
  for (const JunctionMatch& m : matches) {
    const Junction& ja = a[m.index_a];
    const Junction& jb = b[m.index_b];
    const int identity = same(m.index_a, m.index_b);
    const Eigen::Vector2d ta = JudgedPixel(d.frames[i], ja.location), tb = JudgedPixel(d.frames[j], jb.location);
    const bool epipolar_ok = EpipolarConsistent(F_true, ta, tb, bench.epipolar_tolerance);
    const double true_d2 = PointLineDistance(EpipolarLineInImage2(F_true, ta), tb);
    const double true_d1 = PointLineDistance(EpipolarLineInImage1(F_true, tb), ta);
    const double used_d2 = PointLineDistance(EpipolarLineInImage2(F_used, ja.location), jb.location);
    const double used_d1 = PointLineDistance(EpipolarLineInImage1(F_used, jb.location), ja.location);
    const JunctionSimilarity::Bands bands = similarity.BandsOf(m.index_a, m.index_b);
    const PairSimilarity rho = similarity.Rho(m.index_a, m.index_b);
    // The junction of b at the same 3D point as a's (by the corners), if any.
    int true_b = -1;
    for (int k = 0; k < static_cast<int>(b.size()) && true_b < 0; ++k) {
      if (SameTrueVertex(d.near_points[i][m.index_a], d.near_points[j][k]) == 1) true_b = k;
    }
    double true_b_rho = -1;
    if (true_b >= 0 && a[m.index_a].NumSegments() == b[true_b].NumSegments()) {
      true_b_rho = similarity.Rho(m.index_a, true_b).rho;
    }
    out << i << "," << j << "," << m.index_a << "," << m.index_b << "," << JunctionTypeName(ja.type) << ","
        << JunctionTypeName(jb.type) << "," << Fixed(ja.location.x(), 2) << "," << Fixed(ja.location.y(), 2)
        << "," << Fixed(jb.location.x(), 2) << "," << Fixed(jb.location.y(), 2) << "," << Fixed(ja.score, 3)
        << "," << Fixed(jb.score, 3) << "," << (epipolar_ok && identity != 0 ? 1 : 0) << ","
        << (epipolar_ok ? 1 : 0) << "," << identity << "," << Fixed(true_d1, 3) << "," << Fixed(true_d2, 3)
        << "," << Fixed(used_d1, 3) << "," << Fixed(used_d2, 3) << "," << Fixed(bands.in_image1, 3) << ","
        << Fixed(bands.in_image2, 3) << "," << Fixed(rho.rho, 4) << "," << Fixed(m.similarity, 4) << ","
        << (refined ? 1 : 0) << "," << (in_first.count({m.index_a, m.index_b}) ? 1 : 0) << "," << true_b
        << "," << (true_b >= 0 ? partner_of_b[true_b] : -2) << ","
        << (true_b >= 0 && true_b != m.index_b && neighbours(m.index_b, true_b) ? 1 : 0) << ","
        << Fixed(true_b_rho, 4) << "," << lengths(ja) << "," << lengths(jb);
    const Eigen::Matrix3d F_truepose = PairInputOf(bench, d.sequence, i, j, true).F;
    const Eigen::Matrix3d F_odometry = input.F;
    for (const Eigen::Matrix3d* F : {&F_true, &F_used, &F_truepose, &F_odometry}) {
      // The epipoles (right and left null vectors of F), pixels.
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(*F, Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Eigen::Vector3d e1 = svd.matrixV().col(2), e2 = svd.matrixU().col(2);
      out << "," << Fixed(e1.x() / e1.z(), 2) << "," << Fixed(e1.y() / e1.z(), 2) << ","
          << Fixed(e2.x() / e2.z(), 2) << "," << Fixed(e2.y() / e2.z(), 2);
    }
    out << "\n";
  }
  *csv += out.str();
}

}  // namespace

std::vector<std::string> SplitCommaList(const std::string& text) { return Split(text); }
bool ParseNumberList(const std::string& text, std::vector<double>* values) { return ParseNumbers(text, values); }
bool ParseFramePair(const std::string& text, int* a, int* b) { return ParsePair(text, a, b); }

Status MatchingBenchmarkReport(const MatchingBenchmarkOptions& bench, const MatchingBenchmarkSettings& settings,
                               std::string* text) {
  const std::vector<std::string>& generated_dirs = bench.generated;
  const MatchingOptions& matching = settings.matching;
  const std::vector<double>& sweep_R = bench.table2_R;
  const std::vector<double>& sweep_tau2 = bench.table2_tau2;
  const int vgg_a = bench.table2_vgg_pair[0], vgg_b = bench.table2_vgg_pair[1];
  const int gen_a = bench.table2_generated_pair[0], gen_b = bench.table2_generated_pair[1];
  // Data.
  std::vector<GeneratedData> generated(generated_dirs.size());
  for (size_t k = 0; k < generated_dirs.size(); ++k) {
    std::fprintf(stderr, "benchmark_matching: loading %s\n", generated_dirs[k].c_str());
    if (const Status s = LoadGenerated(bench, generated_dirs[k], settings, &generated[k]); !s.ok()) return s;
  }
  VggData vgg;
  const bool have_vgg = !bench.vgg_sequence.empty();
  if (have_vgg) {
    std::fprintf(stderr, "benchmark_matching: loading %s and %s\n", bench.vgg_sequence.c_str(), bench.vgg_dir.c_str());
    if (const Status s = LoadVgg(bench, bench.vgg_sequence, bench.vgg_dir, settings, &vgg); !s.ok()) return s;
  }

  std::ostringstream report;
  report << "Settings: " << bench.segments << " segments; R = " << matching.max_epipolar_distance_px
         << " px, tau1 = " << matching.tau1 << ", tau2 = " << matching.tau2 << ", rho1 "
         << ToString(matching.rho1_kind) << ", " << (matching.use_topology ? "sigma (topology)" : "rho")
         << ", lambda = " << matching.endpoint_model.lambda << ", mu = " << matching.endpoint_model.mu
         << " /px. Radius " << bench.radius << " px, epipolar tolerance " << bench.epipolar_tolerance
         << " px. Single thread.\n";

  // ---- a. Generated sequences ----
  MethodStats ours_generated, lbd_generated, lbd_mutual_generated;
  RefinementTally refinement_generated;
  std::vector<RefinementCase> refinement_cases;  // VGG, odometry, every gap
  std::vector<std::pair<int, RefinementTally>> refinement_vgg;  // by frames apart
  if (!generated.empty()) {
    report
        << "\n## a. Generated sequences: matches at true vertices\n\n"
        << "Consecutive pairs. A junction is at a vertex when a visible wireframe vertex lies within "
        << bench.radius
        << " px of it (two vertices can: a poster corner 5 mm in front of a cabinet corner, far door "
           "frames). "
        << "Precision: of the matches whose two junctions are both at vertices, those at one same vertex "
        << "(\"nearest\": the nearest vertices are the same, stricter). Recall: of the vertices with a "
           "junction "
        << "within " << bench.radius << " px in both frames, those joined by a match between such junctions; "
        << "\"equal counts\": of those, the ones whose junctions have the same number of segments in both "
           "frames; "
        << "\"recall, equal counts\": of these, the ones joined by a full match (junctions of equal counts, "
           "as the "
        << "paper's rule requires); \"matched partially\": vertices joined by partial matches only "
           "(junctions of "
        << "k and k + 1 segments), part of \"matched\". F error: for the vertices visible "
           "in both frames, the larger distance of the "
        << "true pixels from the other's epipolar line under the F used, median / 95 %.\n\n"
        << "| sequence | F from | pairs | matches | both at vertices | same vertex | **precision** | goal | "
        << "precision, nearest | vertices in both | equal counts | matched | **recall** | goal | recall, "
           "equal counts "
        << "| matched partially | F error (px) "
           "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    auto row = [&](const std::string& name, const char* source, const VertexMatchCounts& c,
                   const std::string& error) {
      report << "| " << name << " | " << source << " | " << c.pairs << " | " << c.matches << " | "
             << c.associated << " | " << c.same_vertex << " | **" << Percent(c.same_vertex, c.associated)
             << "** | " << Goal(c.same_vertex, c.associated, 99) << " | "
             << Percent(c.same_nearest, c.associated) << " | " << c.seen_both << " | "
             << c.seen_both_same_count << " | " << c.matched << " | **" << Percent(c.matched, c.seen_both)
             << "** | " << Goal(c.matched, c.seen_both, 90) << " | "
             << Percent(c.matched_same_count, c.seen_both_same_count) << " | " << c.matched_partial_only
             << " | " << error << " |\n";
    };
    std::ostringstream misses;
    misses << "\nWhy vertices seen in both frames were not matched (first reason that applies, for the pair of "
              "junctions at the vertex that got farthest):\n\n| sequence | F from |";
    for (int k = 0; k < static_cast<int>(MissReason::kNumReasons); ++k) {
      misses << " " << MissReasonName(static_cast<MissReason>(k)) << " |";
    }
    misses << "\n|---|---|---|---|---|---|---|\n";
    VertexMatchCounts totals[2];
    WrongTally wrong_generated;
    for (const GeneratedData& d : generated) {
      for (int use_truth = 1; use_truth >= 0; --use_truth) {
        VertexMatchCounts counts;
        std::vector<double> errors;
        for (size_t i = 0; i + 1 < d.frames.size(); ++i) {
          const int j = static_cast<int>(i) + 1;
          const PairInput input = PairInputOf(bench, d.sequence, i, j, use_truth);
          const Eigen::Matrix3d& F = input.F;
          double match_ms = 0;
          MatchingDiagnostics diagnostics;
          const std::vector<JunctionMatch> matches =
              Match(d.frames[i], d.frames[j], input, matching, &match_ms, &diagnostics);
          if (!use_truth && input.geometry && matching.refine_geometry) {
            refinement_generated.Add(diagnostics, *input.geometry,
                                     PairInputOf(bench, d.sequence, i, j, true).geometry->camera2_T_camera1,
                                     [&](const Eigen::Matrix3d& F_used, std::vector<double>* errors) {
                                       TrueVertexEpipolarErrors(d.truth.frames[i], d.truth.frames[j], F_used, errors);
                                     });
          }
          const VertexMatchCounts pair_counts =
              ScoreVertexMatches(d.frames[i].features.junctions, d.frames[j].features.junctions, d.near_vertices[i],
                                 d.near_vertices[j], matches, F, matching, input.Geometry());
          counts.Add(pair_counts);
          TrueVertexEpipolarErrors(d.truth.frames[i], d.truth.frames[j], F, &errors);
          if (!use_truth) {
            // d: ours with the odometry F, judged like the line matches.
            const Eigen::Matrix3d F_true = FundamentalOf(d.sequence, i, j, true);
            const SameFeature same = GeneratedSame(d.near_vertices[i], d.near_vertices[j]);
            ++ours_generated.pairs;
            ours_generated.features += d.frames[i].features.junctions.size() + d.frames[j].features.junctions.size();
            ours_generated.verdicts.Add(JudgeMatches(MatchPairs(matches), JudgedLocations(d.frames[i]),
                                                     JudgedLocations(d.frames[j]), F_true,
                                                     bench.epipolar_tolerance, same));
            ours_generated.recall.Add({pair_counts.seen_both, pair_counts.matched});
            ours_generated.detect_ms.push_back(d.frames[i].features.detect_ms + d.frames[j].features.detect_ms);
            ours_generated.match_ms.push_back(match_ms);
            AddLbdPair(bench, d.frames[i], d.frames[j], d.lbd_line_id[i], d.lbd_line_id[j], GeneratedLineOf(d, i),
                       GeneratedLineOf(d, j), F_true, &lbd_generated, &lbd_mutual_generated);
            TallyWrong(bench, d.frames[i], d.frames[j], matches, F_true, same, /*identity_only=*/true, &wrong_generated);
          }
        }
        totals[use_truth].Add(counts);
        const char* source = use_truth ? "true poses" : "odometry";
        row(d.name, source, counts, Fixed(Quantile(errors, 0.5), 2) + " / " + Fixed(Quantile(errors, 0.95), 2));
        misses << "| " << d.name << " | " << source << " |";
        for (int k = 0; k < static_cast<int>(MissReason::kNumReasons); ++k) misses << " " << counts.misses[k] << " |";
        misses << "\n";
      }
    }
    for (int use_truth = 1; use_truth >= 0; --use_truth) {
      row("**all**", use_truth ? "true poses" : "odometry", totals[use_truth], "");
    }
    report << misses.str() << "\nThe wrong matches of the precision column (odometry F), by junction type in the "
           << "first frame, with their distance from the true epipolar geometry:\n\n"
           << WrongTable(bench, wrong_generated);
  }

  // ---- b. VGG Corridor ----
  MethodStats ours_vgg, lbd_vgg, lbd_mutual_vgg;
  if (have_vgg) {
    int identified = 0, gt_junctions = 0;
    for (const VggView& v : vgg.truth.views) {
      gt_junctions += static_cast<int>(v.junctions.size());
      for (const auto& ids : v.junction_lines3d) identified += ids.size() >= 2;
    }
    int tracked = 0, corners = 0;
    for (const VggView& v : vgg.truth.views) {
      corners += static_cast<int>(v.corners.size());
      for (int p : v.corner_point3d) tracked += p >= 0;
    }
    report << "\n## b. VGG Corridor: precision against the true projection matrices\n\n"
           << "Matches made with F from the imported sequence (its median K with the simulated odometry, or with its "
           << "true poses) or from bt.NNN.P; judged with F = FundamentalFromProjections(bt.i.P, bt.j.P): correct when "
           << "both locations lie within " << bench.epipolar_tolerance << " px of the other's epipolar line and, where "
           << "ground truth identifies both junctions, they are the same. Identity: the reconstructed Harris corners "
           << "(bt.NNN.corners on a bt.nview-corners track, i.e. a bt.p3d point; " << tracked << " of " << corners
           << " corners) within " << bench.radius << " px of the junction, and ground-truth junctions (JunctionsFromSegments "
           << "on bt.NNN.lines, contact 3 px: " << gt_junctions << " in " << vgg.truth.views.size() << " views, "
           << identified << " of them identified by two 3D lines of bt_original.nview-lines) within " << bench.radius
           << " px. Recall: 3D points with a junction within " << bench.radius
           << " px of one of their corners in both views, joined by a match.\n\n"
           << "| frames apart | F from | pairs | junctions/frame | matches | wrong: epipolar (of which the same 3D point) "
           << "| wrong: identity | "
           << "correct | **precision** | goal | identity known | precision there | 3D points in both | matched | recall |\n"
           << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    // Diagnostic variants: the same matching on fewer junctions.
    const VggData no_border = WithoutJunctions(vgg, [](const cv::Mat& image, const Junction& j) {
      return j.location.x() < 5 || j.location.y() < 5 || j.location.x() > image.cols - 6 || j.location.y() > image.rows - 6;
    });
    const VggData no_t = WithoutJunctions(vgg, [](const cv::Mat&, const Junction& j) { return j.type == JunctionType::kT; });
    struct Variant {
      const char* source;
      const VggData* data;
      const char* label;
    };
    const Variant variants[] = {{"odometry", &vgg, "odometry"},
                                {"true poses", &vgg, "true poses (median K)"},
                                {"bt.NNN.P", &vgg, "bt.NNN.P (exact)"},
                                {"odometry", &no_border, "odometry, junctions within 5 px of the border dropped"},
                                {"odometry", &no_t, "odometry, T junctions dropped"}};
    WrongTally wrong_vgg;
    std::string vgg_matches_csv =
        "i,j,index_a,index_b,type_a,type_b,xa,ya,xb,yb,score_a,score_b,correct,epipolar_ok,identity,true_d1,"
        "true_d2,"
        "used_d1,used_d2,band1,band2,rho,similarity,refined,in_first_pass,true_b,true_b_matched_to,"
        "true_b_neighbour_of_b,true_b_rho,lengths_a,lengths_b,e1x_true,e1y_true,e2x_true,e2y_true,e1x,e1y,"
        "e2x,e2y,e1x_tp,e1y_tp,e2x_tp,e2y_tp,e1x_od,e1y_od,e2x_od,e2y_od\n";
    const int n = static_cast<int>(vgg.frames.size());
    for (int gap = 1; gap <= bench.max_gap; ++gap) {
      for (const Variant& variant : variants) {
        const VggData& d = *variant.data;
        const std::string source = variant.source;
        const bool main_row = gap == 1 && variant.data == &vgg && source == "odometry";
        if (gap > 1 && variant.data != &vgg) continue;
        MatchVerdicts verdicts;
        FeatureRecall recall;
        int pairs = 0;
        double junctions = 0;
        for (int i = 0; i + gap < n; ++i) {
          const int j = i + gap;
          const Eigen::Matrix3d F_true = d.TrueF(i, j);
          const PairInput F =
              source == "bt.NNN.P" ? PairInputOf(bench, F_true) : PairInputOf(bench, d.sequence, i, j, source == "true poses");
          double match_ms = 0;
          MatchingDiagnostics diagnostics;
          const std::vector<JunctionMatch> matches = Match(d.frames[i], d.frames[j], F, matching, &match_ms, &diagnostics);
          if (variant.data == &vgg && source == "odometry" && F.geometry && matching.refine_geometry) {
            if (refinement_vgg.empty() || refinement_vgg.back().first != gap) refinement_vgg.emplace_back(gap, RefinementTally());
            refinement_vgg.back().second.Add(
                diagnostics, *F.geometry, PairInputOf(bench, d.sequence, i, j, true).geometry->camera2_T_camera1,
                [&](const Eigen::Matrix3d& F_used, std::vector<double>* errors) {
                  VggCornerEpipolarErrors(d.truth.views[i], d.truth.views[j], d.sequence.calibration.camera, F_used, errors);
                });
            refinement_cases.push_back(VggRefinementCase(bench, d, i, j, *F.geometry, diagnostics.refinement, matching));
          }
          const MatchVerdicts v = JudgeMatches(MatchPairs(matches), JudgedLocations(d.frames[i]),
                                               JudgedLocations(d.frames[j]), F_true,
                                               bench.epipolar_tolerance, VggSame(d, i, j));
          const VertexMatchCounts points = ScoreVertexMatches(d.frames[i].features.junctions, d.frames[j].features.junctions,
                                                              d.near_points[i], d.near_points[j], matches, F, matching);
          const FeatureRecall r{points.seen_both, points.matched};
          verdicts.Add(v);
          recall.Add(r);
          ++pairs;
          junctions += d.frames[i].features.junctions.size() + d.frames[j].features.junctions.size();
          if (main_row) {
            ++ours_vgg.pairs;
            ours_vgg.features += d.frames[i].features.junctions.size() + d.frames[j].features.junctions.size();
            ours_vgg.verdicts.Add(v);
            ours_vgg.recall.Add(r);
            ours_vgg.detect_ms.push_back(d.frames[i].features.detect_ms + d.frames[j].features.detect_ms);
            ours_vgg.match_ms.push_back(match_ms);
            AddLbdPair(bench, d.frames[i], d.frames[j], d.lbd_line_id[i], d.lbd_line_id[j], VggLineOf(d, i), VggLineOf(d, j),
                       F_true, &lbd_vgg, &lbd_mutual_vgg);
            TallyWrong(bench, d.frames[i], d.frames[j], matches, F_true, VggSame(d, i, j), /*identity_only=*/false, &wrong_vgg);
            if (!bench.vgg_matches_csv.empty() && F.geometry) {
              AppendVggMatchRows(bench, d, i, j, F, matching, matches, diagnostics, &vgg_matches_csv);
            }
          }
        }
        report << "| " << gap << " | " << variant.label << " | " << pairs << " | "
               << Fixed(junctions / (2.0 * std::max(1, pairs)), 0) << " | " << verdicts.matches << " | "
               << verdicts.epipolar_wrong << " (" << verdicts.epipolar_wrong_same << ") | " << verdicts.identity_wrong
               << " | " << verdicts.correct << " | **"
               << Percent(verdicts.correct, verdicts.matches) << "** | "
               << (main_row ? Goal(verdicts.correct, verdicts.matches, 97) : "") << " | "
               << Percent(verdicts.identity_known, verdicts.matches) << " | "
               << Percent(verdicts.correct_known, verdicts.identity_known) << " | " << recall.seen_both << " | "
               << recall.matched << " | " << Percent(recall.matched, recall.seen_both) << " |\n";
      }
    }
    if (!bench.vgg_matches_csv.empty()) {
      if (const Status s = WriteFileAtomically(bench.vgg_matches_csv, vgg_matches_csv); !s.ok())
        return s;
    }
    report << "\nThe wrong matches of the first row, by junction type in the first frame:\n\n" << WrongTable(bench, wrong_vgg);
    // How many of the wrong ones are just beyond the tolerance.
    report << "\nPrecision of the consecutive pairs (odometry F) against the epipolar tolerance of the judgement:\n\n"
           << "| matches of | 1 px | 2 px | 3 px | 5 px |\n|---|---|---|---|---|\n";
    for (const Variant& variant : {variants[0], variants[3]}) {
      const VggData& d = *variant.data;
      report << "| " << variant.label << " |";
      for (double tolerance : {1.0, 2.0, 3.0, 5.0}) {
        MatchVerdicts verdicts;
        for (int i = 0; i + 1 < n; ++i) {
          const std::vector<JunctionMatch> matches =
              Match(d.frames[i], d.frames[i + 1], PairInputOf(bench, d.sequence, i, i + 1, false), matching);
          verdicts.Add(JudgeMatches(MatchPairs(matches), JudgedLocations(d.frames[i]),
                                    JudgedLocations(d.frames[i + 1]), d.TrueF(i, i + 1), tolerance,
                                    VggSame(d, i, i + 1)));
        }
        report << " " << Percent(verdicts.correct, verdicts.matches) << " |";
      }
      report << "\n";
    }
  }

  // ---- c. Table 2 ----
  report << "\n## c. The paper's Table 2: rho against sigma over tau2 and R\n\n"
         << "F from the odometry; tau1 = " << matching.tau1 << ", rho1 " << ToString(matching.rho1_kind)
         << "; correct as in b (true epipolar geometry within " << bench.epipolar_tolerance
         << " px, and the same true vertex / ground-truth junction where known); mismatches = matches - "
            "correct.\n";
  if (have_vgg) {
    if (vgg_a >= static_cast<int>(vgg.frames.size()) || vgg_b >= static_cast<int>(vgg.frames.size())) {
      return Status::Error("--table2_vgg_pair names a frame the VGG sequence does not have");
    }
    const PairInput F = PairInputOf(bench, vgg.sequence, vgg_a, vgg_b, false);
    const Sweep sweep = RunSweep(bench, vgg.frames[vgg_a], vgg.frames[vgg_b], F, vgg.TrueF(vgg_a, vgg_b), VggSame(vgg, vgg_a, vgg_b),
                                 matching, sweep_R, sweep_tau2);
    report << "\n### VGG Corridor, frames " << vgg_a << " and " << vgg_b << " ("
           << vgg.frames[vgg_a].features.junctions.size() << " and " << vgg.frames[vgg_b].features.junctions.size()
           << " junctions)\n\n"
           << SweepTable(sweep);
    if (!bench.image_dir.empty()) {
      const std::vector<JunctionMatch> matches = Match(vgg.frames[vgg_a], vgg.frames[vgg_b], F, matching);
      const std::string path = bench.image_dir + "/vgg_" + std::to_string(vgg_a) + "_" + std::to_string(vgg_b) + ".png";
      if (const Status s = WriteVerdictPicture(bench, path, vgg.frames[vgg_a], vgg.frames[vgg_b], matches,
                                               vgg.TrueF(vgg_a, vgg_b), VggSame(vgg, vgg_a, vgg_b));
          !s.ok()) {
        return s;
      }
    }
  }
  if (!generated.empty()) {
    const GeneratedData& d = generated[0];
    if (gen_a >= static_cast<int>(d.frames.size()) || gen_b >= static_cast<int>(d.frames.size())) {
      return Status::Error("--table2_generated_pair names a frame " + d.name + " does not have");
    }
    const PairInput F = PairInputOf(bench, d.sequence, gen_a, gen_b, false);
    const Eigen::Matrix3d F_true = FundamentalOf(d.sequence, gen_a, gen_b, true);
    const SameFeature same = GeneratedSame(d.near_vertices[gen_a], d.near_vertices[gen_b]);
    const Sweep sweep = RunSweep(bench, d.frames[gen_a], d.frames[gen_b], F, F_true, same, matching, sweep_R, sweep_tau2);
    report << "\n### Generated " << d.name << ", frames " << gen_a << " and " << gen_b << " ("
           << d.frames[gen_a].features.junctions.size() << " and " << d.frames[gen_b].features.junctions.size()
           << " junctions)\n\n"
           << SweepTable(sweep);
    if (!bench.image_dir.empty()) {
      const std::vector<JunctionMatch> matches = Match(d.frames[gen_a], d.frames[gen_b], F, matching);
      const std::string path =
          bench.image_dir + "/" + d.name + "_" + std::to_string(gen_a) + "_" + std::to_string(gen_b) + ".png";
      if (const Status s = WriteVerdictPicture(bench, path, d.frames[gen_a], d.frames[gen_b], matches, F_true, same); !s.ok()) {
        return s;
      }
    }
  }

  // ---- d. LSD + LBD ----
  report << "\n## d. Against OpenCV line_descriptor (LSD + binary LBD, brute-force Hamming)\n\n"
         << "Same pairs (generated: all consecutive pairs of the sequences above; VGG: consecutive pairs), same "
         << "ground truth. Ours: junction matches with the odometry F. LBD: LSDDetector (scale 2, one octave, "
         << "segments >= " << bench.lbd_min_length << " px), BinaryDescriptor::compute, "
         << "BinaryDescriptorMatcher::match (each line of image 1 to its nearest; mutual: kept when each is the "
         << "other's nearest); no epipolar information. A line match is correct when the epipolar band of each "
         << "segment (between its end-points' epipolar lines under the true F) meets the other segment within "
         << bench.epipolar_tolerance << " px and, where either segment lies on a true segment with a known 3D line "
         << "(generated: the wireframe edge's line; VGG: bt_original.nview-lines, bt.l3d), the other lies on that "
         << "line's image (both ends within 2 px, within 3 degrees). A detected segment lies on a true one when "
         << "both ends are within 2 px of its line, within 3 degrees, overlapping it by half its length. Junction "
         << "matches are judged as in a and b. Recall: true features (generated: vertices; VGG: 3D points of the "
         << "reconstructed corners; lines: 3D lines) with a detection on them in both images, joined by a match. "
         << "Times per pair: detection in both images, then matching; "
         << "processor time of the one thread, median over pairs.\n\n"
         << "| data | method | pairs | features/frame | matches/pair | **precision** | identity known | precision there | "
         << "**recall** | detection ms | matching ms | total ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  if (!generated.empty()) {
    report << MethodRow("generated", "junctions (ours, sigma)", ours_generated)
           << MethodRow("generated", "LSD + LBD, nearest", lbd_generated)
           << MethodRow("generated", "LSD + LBD, mutual", lbd_mutual_generated);
  }
  if (have_vgg) {
    report << MethodRow("VGG", "junctions (ours, sigma)", ours_vgg) << MethodRow("VGG", "LSD + LBD, nearest", lbd_vgg)
           << MethodRow("VGG", "LSD + LBD, mutual", lbd_mutual_vgg);
  }

  // ---- f. Geometric verification ----
  if (refinement_generated.pairs > 0 || !refinement_vgg.empty()) {
    report << "\n## f. Geometric verification: the refined pair geometry\n\n"
           << "The pairs of a (odometry) and b (odometry): the pose refined from the first pass's matches with the "
           << "odometry as prior (RefinePairGeometry; gate " << matching.refine_gate_sigmas << " sigma, location sigma "
           << matching.location_sigma_px << " px, at least " << matching.refine_min_inliers
           << " supporting matches), or the odometry where it fell back. Errors of camera2_T_camera1 against the true "
           << "poses: rotation angle, and the angle between the translation directions (the scale is not observable "
           << "from two images); median / 90 %, odometry -> the pose used by the guided pass.\n\n"
           << "| data | pairs | refined | fell back: too few matches | too few inliers | inconsistent with the odometry | "
           << "first-pass matches (median) | inliers (median) | Gauss-Newton steps (median) | "
           << "squared Mahalanobis distance from the odometry (median / max; gate 16.8 for 6 DoF) | rotation error (deg) | "
           << "translation direction error (deg) | epipolar error of true correspondences (px) |\n"
           << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    if (refinement_generated.pairs > 0) report << RefinementRow("generated, consecutive", refinement_generated);
    for (const auto& [gap, tally] : refinement_vgg) {
      report << RefinementRow("VGG, " + std::to_string(gap) + " apart", tally);
    }
  }
  if (!refinement_cases.empty()) {
    report << "\nVGG pairs one by one (odometry). Squared Mahalanobis distances from the odometry pose under its "
           << "covariance (the prior of the refinement; 99 % gate 16.8 for 6 DoF) of: the estimate from the first "
           << "pass's matches, the true pose (the imported sequence's, fitted to its median K), and the estimate "
           << "from the pair's true correspondences (bt.p3d corner tracks, no wrong matches, the same prior and "
           << "settings). Rotation errors against the true pose; median epipolar error of the true correspondences "
           << "under each pose.\n\n"
           << "| pair | outcome | distance: estimate | true pose | estimate from true correspondences (n) | "
           << "rotation error (deg): odometry | estimate | from true correspondences | "
           << "translation direction error (deg): odometry | estimate | from true correspondences | "
           << "epipolar error (px): odometry | true pose | estimate | from true correspondences |\n"
           << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RefinementCase& c : refinement_cases) {
      report << "| " << c.pair << " | " << OutcomeName(c.outcome) << " | " << Fixed(c.estimate_distance, 1) << " | "
             << Fixed(c.truth_distance, 1) << " | " << Fixed(c.true_match_distance, 1) << " (" << c.true_matches
             << ") | " << Fixed(c.rotation_odometry, 3) << " | " << Fixed(c.rotation_estimate, 3) << " | "
             << Fixed(c.rotation_true_matches, 3) << " | " << Fixed(c.direction_odometry, 3) << " | "
             << Fixed(c.direction_estimate, 3) << " | " << Fixed(c.direction_true_matches, 3) << " | "
             << Fixed(c.epipolar_odometry, 2) << " | "
             << Fixed(c.epipolar_truth, 2) << " | " << Fixed(c.epipolar_estimate, 2) << " | "
             << Fixed(c.epipolar_true_matches, 2) << " |\n";
    }
  }

  // ---- e. Speed ----
  report << "\n## e. Speed of MatchJunctions\n\n"
         << "One pair of frames, processor time of the one thread, odometry F, junctions and topology graphs given (detection not "
         << "included); median of " << bench.speed_repeats << " runs per pair. The goal is for about "
         << bench.speed_junctions << " junctions per frame: the VGG frames cut to their " << bench.speed_junctions
         << " highest-scoring junctions (topology graphs rebuilt).\n\n"
         << "| data | pairs | junctions per frame (min..max) | sigma: median over pairs (ms) | max (ms) | "
         << "sigma, first pass only: median (ms) | max (ms) | rho: median (ms) | max (ms) | goal |\n"
         << "|---|---|---|---|---|---|---|---|---|---|\n";
  auto time_pairs = [&](const std::string& name, const std::vector<LoadedFrame>& frames, const Sequence& sequence,
                        bool goal) {
    // The settings as given (sigma), then without the verification and guided pass, then rho.
    std::vector<double> ms_of[3];
    size_t fewest = SIZE_MAX, most = 0;
    for (size_t i = 0; i + 1 < frames.size(); ++i) {
      const PairInput F = PairInputOf(bench, sequence, i, i + 1, false);
      for (int config = 0; config < 3; ++config) {
        MatchingOptions options = matching;
        options.use_topology = config < 2;
        if (config == 1) options.refine_geometry = false;
        std::vector<double> runs;
        for (int r = 0; r < bench.speed_repeats; ++r) {
          double ms = 0;
          Match(frames[i], frames[i + 1], F, options, &ms);
          runs.push_back(ms);
        }
        ms_of[config].push_back(Median(runs));
      }
      for (size_t k : {i, i + 1}) {
        fewest = std::min(fewest, frames[k].features.junctions.size());
        most = std::max(most, frames[k].features.junctions.size());
      }
    }
    const double sigma_median = Median(ms_of[0]);
    report << "| " << name << " | " << ms_of[0].size() << " | " << fewest << ".." << most << " | **"
           << Fixed(sigma_median, 3) << "** | " << Fixed(Quantile(ms_of[0], 1.0), 3);
    for (int config = 1; config < 3; ++config) {
      report << " | " << Fixed(Median(ms_of[config]), 3) << " | " << Fixed(Quantile(ms_of[config], 1.0), 3);
    }
    report << " | " << (!goal ? "" : sigma_median < 1.0 ? "pass (< 1 ms)" : "**miss** (>= 1 ms)") << " |\n";
  };
  if (have_vgg) {
    time_pairs("VGG Corridor, the " + std::to_string(bench.speed_junctions) + " strongest junctions of each frame",
               StrongestJunctions(vgg.frames, bench.speed_junctions), vgg.sequence, true);
    time_pairs("VGG Corridor, all junctions", vgg.frames, vgg.sequence, false);
  }
  for (const GeneratedData& d : generated) time_pairs(d.name + ", all junctions", d.frames, d.sequence, false);

  *text = report.str();
  return Status::Ok();
}

}  // namespace sfm

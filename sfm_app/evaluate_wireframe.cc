// evaluate_wireframe: how close a reconstructed wireframe lies to a generated sequence's true one
// (docs/backend_results.md).
//
//   build/bin/evaluate_wireframe --sequence <generated sequence dir> --output <junction_sfm output dir>
//                                [--threshold 0.05]
//
// Reads <output>/wireframe.ply (junction_sfm's vertices and edges, in the odometry's world frame)
// and the true wireframe of <sequence>/truth/ (ReadGroundTruth). The generator's odometry starts on
// the true first pose, so both are in one frame and no alignment is applied for the main figure:
// precision (the share of reconstructed vertices within --threshold of a true edge) and completeness
// (the share of the seen true edges' length within --threshold of a reconstructed edge), overall and
// per edge direction (sfm_app/wireframe_evaluation.h; docs/metrics.md, "Wireframe").
//
// A second, diagnostic figure takes out what a monocular camera cannot see (docs/bundle_adjustment.md,
// "Parameters and gauge"): the scale about the first camera that best maps the refined
// camera positions (<output>/trajectory_refined.txt) onto the true ones
// (<output>/trajectory_groundtruth.txt) is applied to the vertices before measuring.
//
// Prints one JSON object on stdout:
//   {"vertices": N, "edges": E, "threshold_m": t, "within": n, "share": n/N (precision), "median_m": ..,
//    "p90_m": .., "seen_length_m": .., "covered_length_m": .., "completeness": ..,
//    "edge_length_m": .., "edge_share": (edge precision),
//    "by_direction": {"along": {"vertices": .., "share": .., "seen_length_m": .., "completeness": ..},
//                     "across": {..}, "vertical": {..}},
//    "scaled": {"scale": s, and the same figures}}
// ("scaled" is null when the trajectories are missing). Errors: one line on stderr, exit 1 (bad
// input) or 2 (bad flags).
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "backend/export/ply_io.h"
#include "geometry/tum_io.h"
#include "sequences/generator/ground_truth.h"
#include "sfm_app/wireframe_evaluation.h"

DEFINE_string(sequence, "", "Generated sequence directory with truth/ (required).");
DEFINE_string(output, "", "junction_sfm output directory with wireframe.ply (required).");
DEFINE_double(threshold, 0.05, "Distance, m, within which a vertex counts as on a true edge.");

namespace {

std::string Number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

double Share(double part, double whole) {
  return whole > 0 ? part / whole : std::numeric_limits<double>::quiet_NaN();
}

std::string FiguresJson(const sfm::WireframeFigures& figures) {
  std::string json = "\"within\": " + std::to_string(figures.within) +
                     ", \"share\": " + Number(figures.precision) +
                     ", \"median_m\": " + Number(figures.median_m) + ", \"p90_m\": " + Number(figures.p90_m) +
                     ", \"seen_length_m\": " + Number(figures.seen_length_m) +
                     ", \"covered_length_m\": " + Number(figures.covered_length_m) +
                     ", \"completeness\": " + Number(figures.completeness) +
                     ", \"in_view_length_m\": " + Number(figures.in_view_length_m) +
                     ", \"in_view_share\": " + Number(Share(figures.in_view_length_m, figures.seen_length_m)) +
                     ", \"completeness_in_view\": " +
                     Number(Share(figures.covered_in_view_length_m, figures.in_view_length_m)) +
                     ", \"edge_length_m\": " + Number(figures.edge_length_m) +
                     ", \"edge_share\": " + Number(figures.edge_precision) + ", \"by_direction\": {";
  for (int k = 0; k < sfm::kEdgeDirections; ++k) {
    json += std::string(k ? ", " : "") + "\"" + sfm::EdgeDirectionName(static_cast<sfm::EdgeDirection>(k)) +
            "\": {\"vertices\": " + std::to_string(figures.vertices_by_direction[k]) + ", \"share\": " +
            Number(Share(figures.within_by_direction[k], figures.vertices_by_direction[k])) +
            ", \"seen_length_m\": " + Number(figures.seen_length_by_direction[k]) + ", \"completeness\": " +
            Number(Share(figures.covered_length_by_direction[k], figures.seen_length_by_direction[k])) + "}";
  }
  return json + "}";
}

int Fail(const std::string& message) {
  std::fprintf(stderr, "evaluate_wireframe: %s\n", message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage("evaluate_wireframe --sequence <generated sequence> --output <junction_sfm output>");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  google::InitGoogleLogging(argv[0]);
  if (FLAGS_sequence.empty() || FLAGS_output.empty() || !(FLAGS_threshold > 0)) {
    std::fprintf(stderr, "evaluate_wireframe: --sequence and --output are required, --threshold must be > 0\n");
    return 2;
  }
  namespace fs = std::filesystem;
  sfm::GroundTruth truth;
  sfm::Status status = sfm::ReadGroundTruth(FLAGS_sequence, &truth);
  if (!status.ok()) return Fail(status.message());
  if (truth.wireframe.edges.empty()) return Fail(FLAGS_sequence + "/truth: the true wireframe has no edge");
  sfm::ReconstructedWireframe wireframe;
  status = sfm::ReadPly((fs::path(FLAGS_output) / "wireframe.ply").string(), &wireframe);
  if (!status.ok()) return Fail(status.message());

  sfm::WireframeEvaluationOptions options;
  options.threshold_m = FLAGS_threshold;
  const std::vector<bool> seen = sfm::SeenTrueEdges(truth, options.min_views);
  const std::vector<sfm::EdgeDirection> direction = sfm::ClassifyTrueEdges(truth);
  const sfm::TrueEdgeViews views = sfm::ViewsOfTrueEdges(truth);
  const auto measure = [&](const std::vector<Eigen::Vector3d>& vertices) {
    return sfm::EvaluateWireframe(vertices, wireframe.edges, truth.wireframe, seen, direction, options, &views);
  };
  const sfm::WireframeFigures plain = measure(wireframe.vertices);

  // Diagnostic: the refined map scaled about the first camera by the scale that best maps the
  // refined camera positions onto the true ones. The first pose is shared (the odometry starts on
  // the true one and bundle adjustment holds it), so the scale is all that is left to take out. A
  // full similarity (Umeyama) is not used: on a straight corridor the camera positions are nearly
  // collinear, the rotation about the line of travel is decided by centimetres of noise, and one
  // such fit turned a corridor's wireframe (share 0.074 for 0.907).
  std::string scaled = "null";
  std::vector<sfm::StampedPose> refined, groundtruth;
  const fs::path refined_path = fs::path(FLAGS_output) / "trajectory_refined.txt";
  const fs::path truth_path = fs::path(FLAGS_output) / "trajectory_groundtruth.txt";
  if (fs::exists(refined_path) && fs::exists(truth_path) &&
      sfm::ReadTumTrajectory(refined_path.string(), &refined).ok() &&
      sfm::ReadTumTrajectory(truth_path.string(), &groundtruth).ok() && refined.size() == groundtruth.size() &&
      refined.size() >= 2) {
    // s = argmin sum |t_i - c - s (r_i - c)|^2 = sum (t_i - c).(r_i - c) / sum |r_i - c|^2, c the
    // first camera centre (the refined one; the true one is the same up to rounding).
    const Eigen::Vector3d first = refined.front().pose.translation;
    double numerator = 0, denominator = 0;
    for (size_t i = 0; i < refined.size(); ++i) {
      const Eigen::Vector3d r = refined[i].pose.translation - first;
      numerator += (groundtruth[i].pose.translation - first).dot(r);
      denominator += r.squaredNorm();
    }
    const double scale = numerator / denominator;
    if (std::isfinite(scale) && scale > 0) {
      std::vector<Eigen::Vector3d> moved;
      moved.reserve(wireframe.vertices.size());
      for (const Eigen::Vector3d& v : wireframe.vertices) moved.push_back(first + scale * (v - first));
      const sfm::WireframeFigures aligned = measure(moved);
      scaled = "{\"scale\": " + Number(scale) + ", " + FiguresJson(aligned) + "}";
    }
  }
  std::printf("{\"vertices\": %zu, \"edges\": %zu, \"threshold_m\": %s, %s, \"scaled\": %s}\n",
              wireframe.vertices.size(), wireframe.edges.size(), Number(FLAGS_threshold).c_str(),
              FiguresJson(plain).c_str(), scaled.c_str());
  return 0;
}

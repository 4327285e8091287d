// evaluate_wireframe: how close a reconstructed wireframe lies to a generated sequence's true one
// (docs/backend_results.md).
//
//   build/bin/evaluate_wireframe --sequence <generated sequence dir> --output <junction_sfm output dir>
//                                [--threshold 0.05]
//
// Reads <output>/wireframe.ply (junction_sfm's vertices and edges, in the odometry's world frame)
// and the true wireframe of <sequence>/truth/ (ReadGroundTruth). The generator's odometry starts on
// the true first pose, so both are in one frame and no alignment is applied for the main figure:
// each reconstructed vertex is measured by its distance to the nearest true edge (a 3D segment).
//
// A second, diagnostic figure takes out what a monocular camera cannot see (docs/bundle_adjustment.md,
// "What the camera cannot correct"): the scale about the first camera that best maps the refined
// camera positions (<output>/trajectory_refined.txt) onto the true ones
// (<output>/trajectory_groundtruth.txt) is applied to the vertices before measuring.
//
// Prints one JSON object on stdout:
//   {"vertices": N, "edges": E, "threshold_m": t, "within": n, "share": n/N, "median_m": ..,
//    "p90_m": .., "scaled": {"scale": s, "within": .., "share": .., "median_m": .., "p90_m": ..}}
// ("scaled" is null when the trajectories are missing). Errors: one line on stderr, exit 1 (bad
// input) or 2 (bad flags).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gflags/gflags.h>
#include <glog/logging.h>

#include "backend/export/ply_io.h"
#include "geometry/tum_io.h"
#include "sequences/generator/ground_truth.h"

DEFINE_string(sequence, "", "Generated sequence directory with truth/ (required).");
DEFINE_string(output, "", "junction_sfm output directory with wireframe.ply (required).");
DEFINE_double(threshold, 0.05, "Distance, m, within which a vertex counts as on a true edge.");

namespace {

struct Figures {
  int within = 0;
  double share = std::numeric_limits<double>::quiet_NaN();
  double median = std::numeric_limits<double>::quiet_NaN();
  double p90 = std::numeric_limits<double>::quiet_NaN();
};

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  double t = length2 > 0 ? (p - a).dot(ab) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

Figures Measure(const std::vector<Eigen::Vector3d>& vertices, const sfm::Wireframe& truth, double threshold) {
  Figures figures;
  std::vector<double> distances;
  distances.reserve(vertices.size());
  for (const Eigen::Vector3d& p : vertices) {
    double best = std::numeric_limits<double>::infinity();
    for (const sfm::WireEdge& edge : truth.edges) {
      best = std::min(best, DistanceToSegment(p, truth.vertices[edge.vertex_a], truth.vertices[edge.vertex_b]));
    }
    distances.push_back(best);
    if (best <= threshold) ++figures.within;
  }
  if (!distances.empty()) {
    figures.share = static_cast<double>(figures.within) / distances.size();
    std::sort(distances.begin(), distances.end());
    figures.median = distances[distances.size() / 2];
    figures.p90 = distances[std::min(distances.size() - 1, static_cast<size_t>(0.9 * distances.size()))];
  }
  return figures;
}

std::string Number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string FiguresJson(const Figures& figures) {
  return "\"within\": " + std::to_string(figures.within) + ", \"share\": " + Number(figures.share) +
         ", \"median_m\": " + Number(figures.median) + ", \"p90_m\": " + Number(figures.p90);
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

  const Figures plain = Measure(wireframe.vertices, truth.wireframe, FLAGS_threshold);

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
      const Figures aligned = Measure(moved, truth.wireframe, FLAGS_threshold);
      scaled = "{\"scale\": " + Number(scale) + ", " + FiguresJson(aligned) + "}";
    }
  }
  std::printf("{\"vertices\": %zu, \"edges\": %zu, \"threshold_m\": %s, %s, \"scaled\": %s}\n",
              wireframe.vertices.size(), wireframe.edges.size(), Number(FLAGS_threshold).c_str(),
              FiguresJson(plain).c_str(), scaled.c_str());
  return 0;
}

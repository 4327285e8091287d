// vgg_line_completeness: the share of the VGG corridor's ground-truth 3D lines (bt.l3d) within a
// share of the scene's depth range of a junction_sfm run's wireframe edges, after the similarity
// that aligns the run's refined trajectory with the ground truth (issue 19, "Must show").
//   vgg_line_completeness --vgg ../shared/data/vgg-corridor --sequence <imported> --output <run>
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "backend/export/ply_io.h"
#include "benchmarks/vgg_lines/line_completeness.h"
#include "geometry/alignment.h"
#include "geometry/tum_io.h"
#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/vgg_importer.h"

DEFINE_string(vgg, "", "The VGG data set's folder (bt.l3d and the files import_sequence --format vgg reads).");
DEFINE_string(sequence, "", "The sequence import_sequence --format vgg made of it (groundtruth.txt).");
DEFINE_string(output, "", "junction_sfm's output directory on that sequence.");
DEFINE_double(depth_share, 0.02, "Threshold: this share of the scene's depth range (the true lines' ends in the first camera).");

namespace sfm {
namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "vgg_line_completeness: %s\n", message.c_str());
  return 1;
}

std::vector<Eigen::Vector3d> Positions(const std::vector<StampedPose>& poses) {
  std::vector<Eigen::Vector3d> positions;
  for (const StampedPose& pose : poses) positions.push_back(pose.pose.translation);
  return positions;
}

int Run() {
  ImportedSequence imported;
  VggImportSummary summary;
  Status status = ReadVggSequence(FLAGS_vgg, VggImportOptions(), &imported, &summary);
  if (!status.ok()) return Fail(status.message());
  std::ifstream file(FLAGS_vgg + "/bt.l3d");
  if (!file) return Fail(FLAGS_vgg + "/bt.l3d: cannot be read");
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> lines;
  Eigen::Vector3d a, b;
  while (file >> a.x() >> a.y() >> a.z() >> b.x() >> b.y() >> b.z()) {
    lines.emplace_back(VggFileToWorld(a, summary.world_mirrored), VggFileToWorld(b, summary.world_mirrored));
  }
  std::vector<StampedPose> truth, refined;
  status = ReadTumTrajectory(FLAGS_sequence + "/groundtruth.txt", &truth);
  if (status.ok()) status = ReadTumTrajectory(FLAGS_output + "/trajectory_refined.txt", &refined);
  if (!status.ok()) return Fail(status.message());
  if (truth.size() != refined.size() || truth.empty()) return Fail("the trajectories differ in length");
  ReconstructedWireframe wireframe;
  status = ReadPly(FLAGS_output + "/wireframe.ply", &wireframe);
  if (!status.ok()) return Fail(status.message());
  // The sequence's T_base_camera is the identity (VGG gives camera poses): these are the cameras.
  const Similarity3 truth_S_refined = AlignSim3(Positions(refined), Positions(truth));
  for (Eigen::Vector3d& vertex : wireframe.vertices) vertex = truth_S_refined * vertex;
  const Pose3 camera_T_world = truth.front().pose.Inverse();
  double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
  for (const auto& [p, q] : lines) {
    for (const Eigen::Vector3d& end : {p, q}) {
      const double depth = (camera_T_world * end).z();
      nearest = std::min(nearest, depth);
      farthest = std::max(farthest, depth);
    }
  }
  const double threshold = FLAGS_depth_share * (farthest - nearest);
  const LineCompleteness completeness =
      MeasureLineCompleteness(lines, wireframe.vertices, wireframe.edges, threshold, threshold / 2);
  // The lines within 20 degrees of the direction of travel (first to last camera), which a
  // forward-moving camera sees with the least parallax, apart from the others.
  const Eigen::Vector3d travel = (truth.back().pose.translation - truth.front().pose.translation).normalized();
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> along, other;
  for (const auto& line : lines) {
    const bool is_along = std::abs((line.second - line.first).normalized().dot(travel)) > std::cos(20 * M_PI / 180);
    (is_along ? along : other).push_back(line);
  }
  const LineCompleteness along_completeness =
      MeasureLineCompleteness(along, wireframe.vertices, wireframe.edges, threshold, threshold / 2);
  const LineCompleteness other_completeness =
      MeasureLineCompleteness(other, wireframe.vertices, wireframe.edges, threshold, threshold / 2);
  std::printf("{\"true_lines\": %zu, \"true_length\": %.6g, \"depth_range\": %.6g, \"threshold\": %.6g, "
              "\"edges\": %zu, \"completeness\": %.4f, \"along_travel\": {\"lines\": %zu, \"completeness\": %.4f}, "
              "\"other\": {\"lines\": %zu, \"completeness\": %.4f}}\n",
              lines.size(), completeness.true_length, farthest - nearest, threshold, wireframe.edges.size(),
              completeness.Share(), along.size(), along_completeness.Share(), other.size(), other_completeness.Share());
  return 0;
}

}  // namespace
}  // namespace sfm

int main(int argc, char** argv) {
  gflags::SetUsageMessage("vgg_line_completeness --vgg <VGG folder> --sequence <imported> --output <run>");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_minloglevel = google::GLOG_WARNING;  // the importer's account of its refit is not wanted here
  google::InitGoogleLogging(argv[0]);
  FLAGS_logtostderr = true;
  if (FLAGS_vgg.empty() || FLAGS_sequence.empty() || FLAGS_output.empty()) {
    return sfm::Fail("--vgg, --sequence and --output are required");
  }
  return sfm::Run();
}

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

#include <set>
#include <sstream>
#include <utility>

#include "backend/export/ply_io.h"
#include "frontend/junctions/junctions_json.h"
#include "frontend/sequence/sequence.h"
#include "benchmarks/vgg_lines/line_completeness.h"
#include "geometry/alignment.h"
#include "geometry/tum_io.h"
#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/vgg_importer.h"

DEFINE_string(vgg, "", "The VGG data set's folder (bt.l3d and the files import_sequence --format vgg reads).");
DEFINE_string(sequence, "", "The sequence import_sequence --format vgg made of it (groundtruth.txt).");
DEFINE_string(output, "", "junction_sfm's output directory on that sequence.");
DEFINE_double(support_px, 2, "Image support: a true line's projection within this many pixels of a junction segment.");
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

// The junction segments (location to far end) of every frame of the run, all or only those of
// junctions on a track (tracks.csv), with the true cameras: what the images gave the matcher and
// the triangulation.
Status SupportViews(const Sequence& sequence, const std::vector<StampedPose>& truth, bool tracked_only,
                    std::vector<LineSupportView>* views) {
  std::set<std::pair<int, int>> tracked;  // (frame, junction id)
  if (tracked_only) {
    std::ifstream tracks(FLAGS_output + "/tracks.csv");
    if (!tracks) return Status::Error(FLAGS_output + "/tracks.csv: cannot be read");
    std::string line;
    std::getline(tracks, line);  // header
    while (std::getline(tracks, line)) {
      std::istringstream row(line);
      std::string track, frame, junction;
      std::getline(row, track, ',');
      std::getline(row, frame, ',');
      std::getline(row, junction, ',');
      tracked.insert({std::stoi(frame), std::stoi(junction)});
    }
  }
  views->clear();
  for (size_t f = 0; f < truth.size(); ++f) {
    char name[48];
    std::snprintf(name, sizeof(name), "/junctions/%06zu.json", f);
    const std::string path = FLAGS_output + name;
    std::ifstream file(path);
    if (!file) return Status::Error(path + ": cannot be read");
    std::stringstream text;
    text << file.rdbuf();
    JunctionsFile junctions;
    SFM_RETURN_IF_ERROR(JunctionsFromJson(text.str(), path, &junctions));
    LineSupportView view;
    view.K = sequence.calibration.camera.K();
    const Pose3 camera_T_world = (truth[f].pose * sequence.calibration.base_T_camera).Inverse();
    view.R = camera_T_world.rotation.toRotationMatrix();
    view.t = camera_T_world.translation;
    view.width = junctions.width;
    view.height = junctions.height;
    for (const Junction& junction : junctions.junctions) {
      if (tracked_only && !tracked.count({static_cast<int>(f), junction.id})) continue;
      for (const JunctionSegment& segment : junction.segments) view.segments.emplace_back(junction.location, segment.end);
    }
    views->push_back(std::move(view));
  }
  return Status::Ok();
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
  Sequence sequence;
  status = ReadSequence(FLAGS_sequence, &sequence);
  std::vector<LineSupportView> all_views, tracked_views;
  if (status.ok()) status = SupportViews(sequence, truth, false, &all_views);
  if (status.ok()) status = SupportViews(sequence, truth, true, &tracked_views);
  if (!status.ok()) return Fail(status.message());
  constexpr int kMinViews = 2;  // a line needs two views to be triangulated
  const LineImageSupport detected =
      MeasureLineImageSupport(lines, all_views, FLAGS_support_px, threshold / 2, kMinViews);
  const LineImageSupport tracked =
      MeasureLineImageSupport(lines, tracked_views, FLAGS_support_px, threshold / 2, kMinViews);
  std::printf("{\"image_support\": {\"px\": %.3g, \"visible_in_2\": %.4f, \"detected_in_2\": %.4f, "
              "\"tracked_in_2\": %.4f}, ",
              FLAGS_support_px, detected.visible_length / detected.true_length,
              detected.detected_length / detected.true_length, tracked.detected_length / tracked.true_length);
  std::printf("\"true_lines\": %zu, \"true_length\": %.6g, \"depth_range\": %.6g, \"threshold\": %.6g, "
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

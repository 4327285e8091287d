// colmap_ate: the absolute trajectory error (ATE) and the Sim(3) ATE of a COLMAP model's cameras,
// or of a TUM trajectory, against a sequence's ground truth, computed by the project's own
// alignment (backend/metrics, docs/metrics.md) so that they compare with junction_sfm's metrics.json.
//
//   colmap_ate --sequence <dir> --colmap_model <dir with images.txt>
//   colmap_ate --sequence <dir> --trajectory <TUM file>                     (e.g. trajectory_refined.txt)
//   colmap_ate --sequence <dir> --trajectory <TUM file> --colmap_model <dir> (the trajectory on the
//                                                                             frames COLMAP registered)
//   colmap_ate --sequence <dir> --colmap_camera     (prints COLMAP's camera model and parameters for
//                                                    sequence.yaml's camera: "PINHOLE fx,fy,cx,cy")
//
// Prints one JSON object: frames, registered, missing (frame indices), ate_m, ate_sim3_m, sim3_scale.
// A COLMAP image is the frame whose images.txt path is --colmap_image_prefix + its NAME; a TUM line
// is the frame whose timestamp is within 1 ms of it.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "benchmarks/colmap_ate/colmap_poses.h"
#include "geometry/tum_io.h"
#include "util/json_format.h"
#include "util/number_text.h"

DEFINE_string(sequence, "", "Sequence directory with groundtruth.txt. Required.");
DEFINE_string(colmap_model, "", "COLMAP text model directory (images.txt is read).");
DEFINE_string(colmap_image_prefix, "images/",
              "Prepended to a COLMAP image NAME to give its path in the sequence's images.txt.");
DEFINE_bool(
    colmap_camera, false,
    "Print the COLMAP camera model and parameters of sequence.yaml's camera and exit: PINHOLE without "
    "distortion, OPENCV (k1 k2 p1 p2) when k3 is 0, else FULL_OPENCV, OPENCV_FISHEYE (k1 k2 k3 k4) for "
    "distortion_model equidistant; cx, cy in COLMAP's pixel convention.");
DEFINE_string(trajectory, "",
              "TUM trajectory of camera poses world_T_camera, matched to frames by timestamp.");

namespace {

// COLMAP puts the centre of the top-left pixel at (0.5, 0.5), OpenCV (and sequence.yaml) at (0, 0);
// backend/export/colmap_model.cc shifts its principal point the same way.
constexpr double kColmapPixelShift = 0.5;

std::string ColmapCamera(const sfm::Camera& camera) {
  std::string params = sfm::ShortestNumberText(camera.fx) + "," + sfm::ShortestNumberText(camera.fy) + "," +
                       sfm::ShortestNumberText(camera.cx + kColmapPixelShift) + "," +
                       sfm::ShortestNumberText(camera.cy + kColmapPixelShift);
  if (!camera.HasDistortion()) return "PINHOLE " + params;
  for (int i = 0; i < 4; ++i) params += "," + sfm::ShortestNumberText(camera.distortion[i]);
  if (camera.model == sfm::DistortionModel::kEquidistant) return "OPENCV_FISHEYE " + params;  // k1 k2 k3 k4
  if (camera.distortion[4] == 0) return "OPENCV " + params;
  // FULL_OPENCV: k1 k2 p1 p2 k3 k4 k5 k6, the rational terms k4..k6 zero (OpenCV's 5-term model).
  return "FULL_OPENCV " + params + "," + sfm::ShortestNumberText(camera.distortion[4]) + ",0,0,0";
}

int Fail(const sfm::Status& status) {
  std::fprintf(stderr, "colmap_ate: %s\n", status.message().c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "ATE and Sim(3) ATE of a COLMAP model or a TUM trajectory against a sequence's ground truth.\n"
      "  colmap_ate --sequence <dir> [--colmap_model <dir>] [--trajectory <TUM file>]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  if (FLAGS_colmap_camera && !FLAGS_sequence.empty() && argc == 1) {
    sfm::Calibration calibration;
    const sfm::Status status = sfm::ReadCalibration(FLAGS_sequence + "/sequence.yaml", &calibration);
    if (!status.ok()) return Fail(status);
    std::printf("%s\n", ColmapCamera(calibration.camera).c_str());
    return 0;
  }
  if (argc > 1 || FLAGS_sequence.empty() || (FLAGS_colmap_model.empty() && FLAGS_trajectory.empty())) {
    std::fprintf(stderr, "colmap_ate: give --sequence and --colmap_model and/or --trajectory (see --help)\n");
    return 2;
  }
  sfm::Sequence sequence;
  sfm::Status status = sfm::ReadSequence(FLAGS_sequence, &sequence);
  if (!status.ok()) return Fail(status);

  std::map<int, sfm::Pose3> colmap_by_frame;
  if (!FLAGS_colmap_model.empty()) {
    std::map<std::string, sfm::Pose3> by_name;
    const std::string images_txt = FLAGS_colmap_model + "/images.txt";
    status = sfm::ReadColmapImagePoses(images_txt, &by_name);
    if (!status.ok()) return Fail(status);
    std::map<std::string, int> frame_of_path;
    for (const sfm::Frame& frame : sequence.frames) frame_of_path[frame.image_path] = frame.index;
    for (const auto& [name, pose] : by_name) {
      const auto found = frame_of_path.find(FLAGS_colmap_image_prefix + name);
      if (found == frame_of_path.end()) {
        return Fail(sfm::Status::Error(images_txt + ": image " + name + " is not in " + FLAGS_sequence +
                                       "/images.txt (with prefix '" + FLAGS_colmap_image_prefix + "')"));
      }
      colmap_by_frame[found->second] = pose;
    }
  }

  std::map<int, sfm::Pose3> estimated = colmap_by_frame;
  if (!FLAGS_trajectory.empty()) {
    std::vector<sfm::StampedPose> poses;
    status = sfm::ReadTumTrajectory(FLAGS_trajectory, &poses);
    if (!status.ok()) return Fail(status);
    estimated.clear();
    for (const sfm::StampedPose& stamped : poses) {
      for (const sfm::Frame& frame : sequence.frames) {
        if (std::abs(frame.timestamp - stamped.timestamp) > sfm::kTimestampTolerance) continue;
        if (FLAGS_colmap_model.empty() || colmap_by_frame.count(frame.index))
          estimated[frame.index] = stamped.pose;
      }
    }
  }

  sfm::FrameSubsetDrift drift;
  status = sfm::ComputeFrameSubsetDrift(sequence, estimated, &drift);
  if (!status.ok()) return Fail(status);
  const std::set<int> registered(drift.registered.begin(), drift.registered.end());
  std::string missing;
  for (int i = 0; i < drift.frames; ++i) {
    if (!registered.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  }
  std::printf(
      "{\"frames\": %d, \"registered\": %zu, \"missing\": [%s], \"ate_m\": %s, \"ate_sim3_m\": %s, "
      "\"sim3_scale\": %s}\n",
      drift.frames, drift.registered.size(), missing.c_str(), sfm::JsonNumber(drift.ate_m).c_str(),
      sfm::JsonNumber(drift.ate_sim3_m).c_str(), sfm::JsonNumber(drift.sim3_scale).c_str());
  return 0;
}

// match_junctions: junction matches between any two frames of a sequence (docs/matching.md,
// docs/matching_results.md).
//
//   build/bin/match_junctions --sequence <dir> --frame_a i --frame_b j [--csv out.csv] [--overlay out.png]
//                             [--fundamental odometry|groundtruth] [detection and matching flags]
//
// Both images are undistorted (ImageUndistorter), segments, junctions and topology graphs are
// detected, and the junctions matched (paper sections 3-4) under F from the calibration and the two
// frames' odometry poses (FundamentalFromOdometry; --fundamental=groundtruth uses groundtruth.txt
// instead), with the pose's uncertainty from sequence.yaml's odometry noise model
// (PairGeometryFromOdometry: per-pair epipolar band and cheirality; --match_pose=false: F only).
// Writes the matches as SPEC section 3 CSV (header id_a,id_b,similarity; junction ids of frame_a
// and frame_b) and a side-by-side PNG in the style of the paper's Fig. 6: each matched
// pair numbered, corresponding junction segments in the same colour, unmatched junctions in grey.
// Errors are one line on stderr and a non-zero exit, with nothing written: 2 for bad flags, 1 for
// bad input or an output that cannot be written.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "geometry/epipolar.h"
#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/matches_csv.h"
#include "frontend/segments/segment_detector.h"
#include "frontend/junctions/undistorted_junctions.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "pipeline/overlay/match_overlay.h"
#include "sfm_app/flags/detector_flags.h"

namespace {
const sfm::MatchingOptions kMatchingDefaults;
}  // namespace

DEFINE_string(sequence, "", "Sequence directory (SPEC section 1). Required.");
DEFINE_int32(frame_a, -1, "First frame (0-based index into images.txt). Required.");
DEFINE_int32(frame_b, -1, "Second frame, any other frame of the sequence. Required.");
DEFINE_string(csv, "", "Write the matches here (SPEC section 3: id_a,id_b,similarity).");
DEFINE_string(overlay, "", "Write the side-by-side match picture here (.png).");
DEFINE_int32(overlay_scale, 1, "Enlarge the picture this many times (1..4).");
DEFINE_string(fundamental, "odometry",
              "Where F comes from: 'odometry' (odometry.txt, as junction_sfm) or 'groundtruth' (groundtruth.txt).");
// The detector and matching flags shared with the other apps (--segments, --endpoint_lambda,
// --match_tau1, ...): sfm_app/flags/detector_flags.h.
DEFINE_bool(match_pose, true,
            "Match with the pair's pose and sequence.yaml's odometry noise (PairGeometryFromOdometry): per-pair "
            "epipolar band and cheirality. false: F only, with the fixed R of --match_max_distance.");
DEFINE_double(match_location_sigma, kMatchingDefaults.location_sigma_px,
              "With --match_pose: standard deviation of a junction location, px.");

namespace {

int Fail(int code, const std::string& message) {
  std::fprintf(stderr, "match_junctions: %s\n", message.c_str());
  return code;
}

std::string ParentOf(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

// Flags -> options; false with a one-line message for a bad value.
bool OptionsFromFlags(sfm::SegmentDetectorOptions* segments, sfm::JunctionDetectorOptions* junctions,
                      sfm::MatchingOptions* matching, std::string* error) {
  if (!sfm::SegmentMethodFromFlags(segments, error)) return false;
  if (!sfm::MatchingFromFlags(junctions, matching, error)) return false;
  matching->location_sigma_px = FLAGS_match_location_sigma;
  for (const sfm::Status& check : {segments->Check(), junctions->Check(), matching->Check()}) {
    if (!check.ok()) {
      *error = check.message();
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "junction matches between two frames of a sequence, as CSV and a Fig. 6-style picture.\n"
      "  match_junctions --sequence <dir> --frame_a i --frame_b j [--csv out.csv] [--overlay out.png] "
      "[flags]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

  // Flags.
  if (argc > 1) return Fail(2, std::string("unexpected argument '") + argv[1] + "' (flags are --name=value; see --help)");
  if (FLAGS_sequence.empty()) return Fail(2, "--sequence is required: the sequence directory");
  if (FLAGS_frame_a < 0 || FLAGS_frame_b < 0) return Fail(2, "--frame_a and --frame_b are required: frame indices >= 0");
  if (FLAGS_frame_a == FLAGS_frame_b) return Fail(2, "--frame_a and --frame_b must be two different frames");
  if (FLAGS_overlay_scale < 1 || FLAGS_overlay_scale > 4) return Fail(2, "--overlay_scale must be in 1..4");
  if (!FLAGS_overlay.empty() && std::filesystem::path(FLAGS_overlay).extension() != ".png") {
    return Fail(2, "--overlay must name a .png file, not '" + FLAGS_overlay + "'");
  }
  if (FLAGS_fundamental != "odometry" && FLAGS_fundamental != "groundtruth") {
    return Fail(2, "--fundamental must be 'odometry' or 'groundtruth', not '" + FLAGS_fundamental + "'");
  }
  sfm::SegmentDetectorOptions segment_options;
  sfm::JunctionDetectorOptions junction_options;
  sfm::MatchingOptions matching_options;
  std::string error;
  if (!OptionsFromFlags(&segment_options, &junction_options, &matching_options, &error)) return Fail(2, error);
  sfm::UndistortInterpolation interpolation;
  if (!sfm::UndistortInterpolationFromFlags(&interpolation, &error)) return Fail(2, error);

  // Input, and output places, all checked before any work.
  sfm::Sequence sequence;
  if (const sfm::Status s = sfm::ReadSequence(FLAGS_sequence, &sequence); !s.ok()) return Fail(1, s.message());
  const int n = static_cast<int>(sequence.frames.size());
  for (int frame : {FLAGS_frame_a, FLAGS_frame_b}) {
    if (frame >= n) {
      return Fail(1, FLAGS_sequence + ": has " + std::to_string(n) + " frames (0.." + std::to_string(n - 1) +
                         "), no frame " + std::to_string(frame));
    }
  }
  const bool use_groundtruth = FLAGS_fundamental == "groundtruth";
  if (use_groundtruth && !sequence.has_groundtruth) {
    return Fail(1, FLAGS_sequence + ": --fundamental=groundtruth but the sequence has no groundtruth.txt");
  }
  const sfm::Frame& frame_a = sequence.frames[FLAGS_frame_a];
  const sfm::Frame& frame_b = sequence.frames[FLAGS_frame_b];
  const sfm::Calibration& calibration = sequence.calibration;
  const sfm::Pose3& base_a = use_groundtruth ? *frame_a.world_T_base_groundtruth : frame_a.world_T_base_odometry;
  const sfm::Pose3& base_b = use_groundtruth ? *frame_b.world_T_base_groundtruth : frame_b.world_T_base_odometry;
  const sfm::Pose3 camera_b_T_camera_a =
      (base_b * calibration.base_T_camera).Inverse() * (base_a * calibration.base_T_camera);
  // F of a pure rotation is zero: no epipolar geometry to match with. 1e-9 of the scene's units.
  if (!(camera_b_T_camera_a.translation.norm() > 1e-9)) {
    return Fail(1, "frames " + std::to_string(FLAGS_frame_a) + " and " + std::to_string(FLAGS_frame_b) +
                       ": the camera does not move between them (per " + FLAGS_fundamental +
                       "), so F is undefined");
  }
  const Eigen::Matrix3d F =
      sfm::FundamentalFromOdometry(calibration.camera.K(), calibration.base_T_camera, base_a, base_b);
  // The pose and its uncertainty from sequence.yaml's odometry noise model (also with
  // --fundamental=groundtruth: the band is then the one the odometry would have had).
  const sfm::PairGeometry geometry = sfm::PairGeometryFromOdometry(
      calibration.camera.K(), calibration.base_T_camera, base_a, base_b,
      calibration.odometry_noise.translation_sigma, calibration.odometry_noise.rotation_sigma,
      std::abs(FLAGS_frame_b - FLAGS_frame_a));
  cv::Mat image_a, image_b;
  if (const sfm::Status s = sfm::LoadFrameImage(sequence, FLAGS_frame_a, &image_a); !s.ok()) return Fail(1, s.message());
  if (const sfm::Status s = sfm::LoadFrameImage(sequence, FLAGS_frame_b, &image_b); !s.ok()) return Fail(1, s.message());
  std::error_code fs_error;
  for (const std::string* output : {&FLAGS_csv, &FLAGS_overlay}) {
    if (output->empty()) continue;
    if (std::filesystem::is_directory(*output, fs_error)) return Fail(1, *output + ": is a directory, not a file");
    if (const sfm::Status s = sfm::EnsureWritableDirectory(ParentOf(*output)); !s.ok()) return Fail(1, s.message());
  }

  // Detection and matching.
  const auto start = std::chrono::steady_clock::now();
  // Detection on the view --undistort_full_view asks for (junctions in K's pixels either way); the
  // match picture shows the undistorted images of the stored size.
  const sfm::ImageUndistorter detector_view(calibration.camera, interpolation, sfm::UndistortViewFromFlags());
  const sfm::Junctions junctions_a =
      sfm::DetectUndistortedJunctions(detector_view, image_a, segment_options, junction_options);
  const sfm::Junctions junctions_b =
      sfm::DetectUndistortedJunctions(detector_view, image_b, segment_options, junction_options);
  const sfm::TopologyGraph graph_a = sfm::BuildTopologyGraph(junctions_a);
  const sfm::TopologyGraph graph_b = sfm::BuildTopologyGraph(junctions_b);
  const auto matched = std::chrono::steady_clock::now();
  const std::vector<sfm::JunctionMatch> matches =
      FLAGS_match_pose ? sfm::MatchJunctions(junctions_a, graph_a, junctions_b, graph_b, geometry, matching_options)
                       : sfm::MatchJunctions(junctions_a, graph_a, junctions_b, graph_b, F, matching_options);
  const double detect_ms = std::chrono::duration<double, std::milli>(matched - start).count();
  const double match_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - matched).count();

  // Output.
  if (!FLAGS_csv.empty()) {
    if (const sfm::Status s = sfm::WriteFileAtomically(FLAGS_csv, sfm::MatchesCsv(junctions_a, junctions_b, matches)); !s.ok()) {
      return Fail(1, s.message());
    }
  }
  if (!FLAGS_overlay.empty()) {
    const sfm::ImageUndistorter undistorter(calibration.camera, interpolation);
    const cv::Mat grey_a = undistorter.Apply(image_a), grey_b = undistorter.Apply(image_b);
    const cv::Mat picture =
        sfm::DrawMatchOverlay(grey_a, junctions_a, grey_b, junctions_b, matches, FLAGS_overlay_scale);
    std::vector<uchar> png;
    if (!cv::imencode(".png", picture, png)) return Fail(1, FLAGS_overlay + ": PNG encoding failed");
    if (const sfm::Status s = sfm::WriteFileAtomically(FLAGS_overlay, std::string(png.begin(), png.end()));
        !s.ok()) {
      return Fail(1, s.message());
    }
  }
  std::printf("match_junctions: frames %d and %d: %zu and %zu junctions, %zu matches (F from %s; %s; "
              "%s; detection %.1f ms, matching %.2f ms)\n",
              FLAGS_frame_a, FLAGS_frame_b, junctions_a.size(), junctions_b.size(), matches.size(),
              FLAGS_fundamental.c_str(), matching_options.use_topology ? "sigma" : "rho",
              FLAGS_match_pose ? "pose band and cheirality" : "fixed R", detect_ms, match_ms);
  return 0;
}

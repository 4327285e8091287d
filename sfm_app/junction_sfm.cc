// junction_sfm: junction-based structure from motion on a sequence (SPEC section 2).
//
//   build/bin/junction_sfm --sequence <sequence dir> --output <output dir>
//
// Without --sequence it runs the default sequence shipped under sequences/default (installed under
// share/junction_sfm/default). Flag defaults are taken from the option structs, so --help always
// shows the values the code uses; docs/ says how each was chosen.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "sfm_app/flags/detector_flags.h"
#include "pipeline/pipeline.h"
#include "sfm_app/help.h"
#include "sfm_app/run_junction_sfm.h"

namespace {
const sfm::PipelineOptions kDefaults;

const char* FloorPriorName(sfm::FloorPriorMode mode) {
  switch (mode) {
    case sfm::FloorPriorMode::kOff: return "off";
    case sfm::FloorPriorMode::kAuto: return "auto";
    case sfm::FloorPriorMode::kOn: return "on";
  }
  return "auto";
}

// The shipped sequence: beside an installed program (bin/../share/junction_sfm/default, the install
// rule of sfm_app/CMakeLists.txt), else the source tree's sequences/default the program was built from.
std::string DefaultSequence() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = program.parent_path() / SFM_INSTALLED_SEQUENCE_FROM_BIN;
    if (std::filesystem::is_regular_file(installed / "sequence.yaml", error))
      return installed.lexically_normal();
  }
  return SFM_DEFAULT_SEQUENCE;
}

}  // namespace

DEFINE_string(sequence, DefaultSequence(),
              "Sequence directory (SPEC section 1: sequence.yaml, images.txt, odometry.txt, optional "
              "groundtruth.txt). Default: the sequence shipped in sequences/default.");
DEFINE_string(output, "output",
              "Output directory, replaced whole by a run that succeeds (written beside it, then swapped in); "
              "an existing directory must be empty or an earlier run's output. The run's log is "
              "junction_sfm.log in it.");
DEFINE_bool(progress, true, "Show a progress line on stderr (only when stderr is a terminal).");
// The detector and matching flags (--segments, --endpoint_lambda, --match_*, ...) are shared with the other
// apps: sfm_app/flags/detector_flags.h.

DEFINE_bool(bundle_adjustment, kDefaults.bundle_adjustment,
            "Refine poses, points and lines with the Ceres bundle adjustment (false: outputs use the odometry).");
DEFINE_double(ba_outlier_threshold, kDefaults.bundle_adjustment_options.outlier_threshold_px,
              "Bundle adjustment: observations with a larger error (px) are removed and the problem solved again.");
DEFINE_double(ba_loss_scale, kDefaults.bundle_adjustment_options.robust_loss_scale_px,
              "Bundle adjustment: scale (px) of the robust loss on image residuals.");
DEFINE_string(floor_prior, FloorPriorName(kDefaults.bundle_adjustment_options.floor_prior),
              "Bundle adjustment: ground-plane prior that fixes the odometry's scale: 'auto' (when the rig, the "
              "odometry and the map show a ground robot with its base origin on the floor), 'on' (whenever a floor "
              "plane is found) or 'off'.");
DEFINE_string(
    odometry_rotation_bias,
    kDefaults.bundle_adjustment_options.estimate_odometry_rotation_bias            ? "on"
    : kDefaults.bundle_adjustment_options.estimate_odometry_rotation_bias_on_floor ? "auto"
                                                                                   : "off",
    "Bundle adjustment: estimate the odometry's constant rotation increment per step jointly with the "
    "poses: 'on', 'off' or 'auto' (where the floor prior may apply: a ground robot's rig and planar "
    "odometry).");
DEFINE_int32(threads, kDefaults.bundle_adjustment_options.num_threads, "Threads for the bundle adjustment.");
DEFINE_bool(extend_tracks, kDefaults.extend_tracks,
            "Track extension: project every point landmark into the frames its track misses and join the one "
            "compatible junction inside its uncertainty gate, or merge the track it belongs to; inside the "
            "bundle adjustment, after its first fine solve.");
DEFINE_double(extend_tracks_pixel_sigma, kDefaults.track_extension.pixel_sigma_px,
              "Track extension: pixel noise of a junction location in the gate, pixels.");
DEFINE_double(extend_tracks_max_gate_px, kDefaults.track_extension.max_gate_px,
              "Track extension: the largest gate radius, pixels (a wider gate is not searched).");
DEFINE_double(extend_tracks_max_angle_deg, kDefaults.track_extension.max_angle_deg,
              "Track extension: the largest angle between a junction segment and its predicted direction, degrees.");
DEFINE_double(wireframe_tolerance_m, kDefaults.triangulation.wireframe.tolerance_m,
              "Wireframe selection: an accuracy asked of the drawn map, metres (0: off): the least determined "
              "vertices are dropped until the predicted share within it is --wireframe_tolerance_share "
              "(docs/tracks_and_triangulation.md, \"An accuracy asked of the map\").");
DEFINE_double(wireframe_tolerance_share, kDefaults.triangulation.wireframe.tolerance_share,
              "Wireframe selection: the share of drawn vertices asked to be within --wireframe_tolerance_m.");
DEFINE_double(wireframe_far_end_at_point_px, kDefaults.triangulation.wireframe.far_end_at_point_px,
              "Wireframe selection: a line's far end is taken at a drawn junction point when its observed "
              "image lines lie within this many pixels of its projections (median over the views, across "
              "the lines; 0: off; docs/tracks_and_triangulation.md, \"Far ends at junction points\").");
DEFINE_double(wireframe_far_end_along_px, kDefaults.triangulation.wireframe.far_end_along_px,
              "Wireframe selection, --wireframe_far_end_at_point_px: the largest median distance, pixels, "
              "along the observed image lines between the point's projections and the far end-points.");

namespace {

// --help: the program's flags by stage, one line each (sfm_app/help.h). tests/app checks that every
// flag of the program is listed here.
constexpr const char* kRun = "Input, output and run";
constexpr const char* kDetection = "Detection (segments and junctions)";
constexpr const char* kMatching = "Matching (pairs of frames)";
constexpr const char* kBackEnd = "Back end (tracks and bundle adjustment)";
constexpr const char* kWireframe = "Output: wireframe selection";
const std::vector<sfm::HelpFlag> kHelpTable = {
    {"sequence", kRun, "Sequence directory (docs/formats.md); default: the shipped example."},
    {"output", kRun, "Output directory, replaced whole when the run succeeds."},
    {"threads", kRun, "Threads for the bundle adjustment (1..256)."},
    {"progress", kRun, "Progress line on stderr when it is a terminal."},
    {"segments", kDetection, "Line segment detector: fast | reference."},
    {"undistort_interpolation", kDetection, "Resampling of distorted frames: linear | cubic | lanczos4."},
    {"undistort_full_view", kDetection, "Detect on a canvas holding the distorted image's whole view."},
    {"endpoint_lambda", kDetection, "End-point model: decay beyond the true end-point, 1/px."},
    {"endpoint_mu", kDetection, "End-point model: decay short of the true end-point, 1/px."},
    {"junction_min_probability", kDetection, "Least junction probability of a pair of segments, (0, 1]."},
    {"match_pose_band", kMatching,
     "Search band from the odometry's uncertainty (false: --match_max_distance)."},
    {"match_band_sigmas", kMatching, "Search band width, standard deviations of the epipolar distance."},
    {"match_max_distance", kMatching, "Fixed search band half-width, px (with --match_pose_band=false)."},
    {"match_tau1", kMatching, "Least similarity of a match."},
    {"match_tau2", kMatching, "How much the best candidate must beat the second."},
    {"match_rho1", kMatching, "Epipolar similarity term: exponential | linear."},
    {"match_cheirality", kMatching, "Reject matches that would triangulate behind a camera."},
    {"match_topology", kMatching, "Match on junction topology rather than on plain similarity."},
    {"match_refine", kMatching, "Refine each pair's pose from its matches, then match again."},
    {"match_refine_gate", kMatching, "With --match_refine: band of the second pass, sigmas."},
    {"match_refine_min_inliers", kMatching, "With --match_refine: fewest matches to trust the refined pose."},
    {"bundle_adjustment", kBackEnd, "Refine poses, points and lines (false: outputs use the odometry)."},
    {"ba_outlier_threshold", kBackEnd,
     "Observations with a larger error (px) are removed, then solved again."},
    {"ba_loss_scale", kBackEnd, "Scale of the robust loss on image residuals, px."},
    {"floor_prior", kBackEnd, "Ground-plane prior fixing the odometry's scale: auto | on | off."},
    {"odometry_rotation_bias", kBackEnd,
     "Estimate the odometry's constant rotation per step: auto | on | off."},
    {"extend_tracks", kBackEnd, "Extend tracks into the frames they miss during the adjustment."},
    {"extend_tracks_pixel_sigma", kBackEnd, "Track extension: junction location noise, px."},
    {"extend_tracks_max_gate_px", kBackEnd, "Track extension: largest search radius, px."},
    {"extend_tracks_max_angle_deg", kBackEnd, "Track extension: largest segment direction error, degrees."},
    {"wireframe_tolerance_m", kWireframe, "Accuracy asked of the drawn map, m (0: off)."},
    {"wireframe_tolerance_share", kWireframe, "Share of drawn vertices asked to be within it."},
    {"wireframe_far_end_at_point_px", kWireframe,
     "Take a line's far end at a junction point within px (0: off)."},
    {"wireframe_far_end_along_px", kWireframe, "Largest distance along the line for that, px."},
};

// The option fields the flags set, with their flags, so that a Check() message names the flag
// (FlagMessage): "--threads=0: must be >= 1", not the option struct's field.
const std::vector<std::pair<std::string, std::string>> kOptionFlags = {
    {"num_threads", "threads"},
    {"robust_loss_scale_px", "ba_loss_scale"},
    {"outlier_threshold_px", "ba_outlier_threshold"},
    {"pixel_sigma_px", "extend_tracks_pixel_sigma"},
    {"max_gate_px", "extend_tracks_max_gate_px"},
    {"max_angle_deg", "extend_tracks_max_angle_deg"},
    {"tolerance_m", "wireframe_tolerance_m"},
    {"tolerance_share", "wireframe_tolerance_share"},
    {"far_end_at_point_px", "wireframe_far_end_at_point_px"},
    {"far_end_along_px", "wireframe_far_end_along_px"},
    {"max_epipolar_distance_px", "match_max_distance"},
    {"tau1", "match_tau1"},
    {"tau2", "match_tau2"},
    {"band_sigmas", "match_band_sigmas"},
    {"refine_gate_sigmas", "match_refine_gate"},
    {"refine_min_inliers", "match_refine_min_inliers"},
    {"min_probability", "junction_min_probability"},
    {"lambda", "endpoint_lambda"},
    {"mu", "endpoint_mu"},
};

// More threads than this are refused: each is a Ceres worker with its own stack, and beyond the
// cores they only slow the solve.
constexpr int kMaxThreads = 256;

// Flags -> options; a one-line message for a flag value that is not one of the choices.
bool OptionsFromFlags(sfm::PipelineOptions* options, std::string* error) {
  options->sequence_dir = FLAGS_sequence;
  options->output_dir = FLAGS_output;
  options->show_progress = FLAGS_progress;
  if (!sfm::UndistortInterpolationFromFlags(&options->undistort_interpolation, error)) return false;
  options->undistort_full_view = sfm::UndistortViewFromFlags() == sfm::UndistortView::kFullView;
  if (!sfm::SegmentMethodFromFlags(&options->segments, error)) return false;
  if (!sfm::MatchingFromFlags(&options->junctions, &options->matching, error)) return false;
  sfm::MatchingRefineFromFlags(&options->matching);
  options->bundle_adjustment = FLAGS_bundle_adjustment;
  options->extend_tracks = FLAGS_extend_tracks;
  options->track_extension.pixel_sigma_px = FLAGS_extend_tracks_pixel_sigma;
  options->track_extension.max_gate_px = FLAGS_extend_tracks_max_gate_px;
  options->track_extension.max_angle_deg = FLAGS_extend_tracks_max_angle_deg;
  options->bundle_adjustment_options.outlier_threshold_px = FLAGS_ba_outlier_threshold;
  options->bundle_adjustment_options.robust_loss_scale_px = FLAGS_ba_loss_scale;
  if (FLAGS_threads < 1 || FLAGS_threads > kMaxThreads) {
    *error = "--threads=" + std::to_string(FLAGS_threads) + ": must be between 1 and " +
             std::to_string(kMaxThreads);
    return false;
  }
  options->bundle_adjustment_options.num_threads = FLAGS_threads;
  options->triangulation.wireframe.tolerance_m = FLAGS_wireframe_tolerance_m;
  options->triangulation.wireframe.tolerance_share = FLAGS_wireframe_tolerance_share;
  options->triangulation.wireframe.far_end_at_point_px = FLAGS_wireframe_far_end_at_point_px;
  options->triangulation.wireframe.far_end_along_px = FLAGS_wireframe_far_end_along_px;
  if (FLAGS_floor_prior == "auto") {
    options->bundle_adjustment_options.floor_prior = sfm::FloorPriorMode::kAuto;
  } else if (FLAGS_floor_prior == "on") {
    options->bundle_adjustment_options.floor_prior = sfm::FloorPriorMode::kOn;
  } else if (FLAGS_floor_prior == "off") {
    options->bundle_adjustment_options.floor_prior = sfm::FloorPriorMode::kOff;
  } else {
    *error = "--floor_prior must be 'auto', 'on' or 'off', not '" + FLAGS_floor_prior + "'";
    return false;
  }
  if (FLAGS_odometry_rotation_bias == "on" || FLAGS_odometry_rotation_bias == "off" ||
      FLAGS_odometry_rotation_bias == "auto") {
    options->bundle_adjustment_options.estimate_odometry_rotation_bias = FLAGS_odometry_rotation_bias == "on";
    options->bundle_adjustment_options.estimate_odometry_rotation_bias_on_floor =
        FLAGS_odometry_rotation_bias == "auto";
  } else {
    *error =
        "--odometry_rotation_bias must be 'on', 'off' or 'auto', not '" + FLAGS_odometry_rotation_bias + "'";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetVersionString(SFM_VERSION);
  sfm::ParseFlagsWithProgramHelp(
      &argc, &argv,
      "junction_sfm: junction-based structure from motion for a ground robot's camera and odometry.\n"
      "  junction_sfm --sequence <sequence dir> --output <output dir> [flags]",
      kHelpTable,
      "Log: junction_sfm.log in the output directory; --v=1 adds detail and copies it to stderr.\n"
      "Version: --version. Guide: docs/user_guide.md.\n");
  google::InitGoogleLogging(argv[0]);
  sfm::ConfigureLogging();

  if (argc > 1) {
    std::fprintf(stderr, "junction_sfm: unexpected argument '%s' (flags are --name=value; see --help)\n", argv[1]);
    return 2;
  }
  sfm::PipelineOptions options;
  std::string error;
  if (!OptionsFromFlags(&options, &error)) {
    std::fprintf(stderr, "junction_sfm: %s\n", error.c_str());
    return 2;
  }
  if (const sfm::Status check = options.Check(); !check.ok()) {
    std::fprintf(stderr, "junction_sfm: %s\n", sfm::FlagMessage(check.message(), kOptionFlags).c_str());
    return 2;
  }
  return sfm::RunIntoOutputDirectory(options);
}

// junction_sfm: junction-based structure from motion on a sequence (SPEC section 2).
//
//   build/bin/junction_sfm --sequence <sequence dir> --output <output dir>
//
// Without --sequence it runs the default sequence shipped under sequences/default. Flag defaults
// are taken from the option structs, so --help always shows the values the code uses; docs/ says
// how each was chosen.
#include <cstdio>
#include <string>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "sfm_app/flags/detector_flags.h"
#include "pipeline/pipeline.h"

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

const char* RetriangulateRefinedName(sfm::RetriangulateRefined mode) {
  switch (mode) {
    case sfm::RetriangulateRefined::kOff:
      return "off";
    case sfm::RetriangulateRefined::kStructure:
      return "structure";
    case sfm::RetriangulateRefined::kFull:
      return "full";
  }
  return "off";
}
}  // namespace

DEFINE_string(sequence, SFM_DEFAULT_SEQUENCE,
              "Sequence directory (SPEC section 1: sequence.yaml, images.txt, odometry.txt, optional "
              "groundtruth.txt). Default: the sequence shipped in sequences/default.");
DEFINE_string(output, "output", "Output directory; created if missing, files of the same names replaced.");
DEFINE_bool(progress, true, "Show a progress line on stderr (only when stderr is a terminal).");
// The detector and matching flags (--segments, --endpoint_lambda, --match_*, ...) are shared with the other
// apps: sfm_app/flags/detector_flags.h.

DEFINE_bool(bundle_adjustment, kDefaults.bundle_adjustment,
            "Refine poses, points and lines with the Ceres bundle adjustment (false: outputs use the odometry).");
DEFINE_double(ba_outlier_threshold, kDefaults.bundle_adjustment_options.outlier_threshold_px,
              "Bundle adjustment: observations with a larger error (px) are removed and the problem solved again.");
DEFINE_int32(ba_observability_rounds, kDefaults.bundle_adjustment_options.observability_rounds,
             "Bundle adjustment: after the last solve, drop the landmarks it made unobservable (a line behind or "
             "through a camera, or without triangulation angle) and solve again, at most this many times.");
DEFINE_bool(ba_inner_iterations_poses, kDefaults.bundle_adjustment_options.inner_iterations_poses,
            "Bundle adjustment: re-solve the poses, the odometry's scale and rotation bias in Ceres's inner "
            "iterations too, not only the landmarks (the solver before session 6; slower, same result).");
DEFINE_bool(ba_single_pose_block, kDefaults.bundle_adjustment_options.single_pose_block,
            "Bundle adjustment: each frame's pose one 7-number Ceres parameter block in the joint solves "
            "(false: a rotation block and a translation block, the layout before session 6; slower).");
DEFINE_bool(ba_inner_iterations_throughout, kDefaults.bundle_adjustment_options.inner_iterations_throughout,
            "Bundle adjustment: keep Ceres's inner iterations on through every step of a solve (false: Ceres "
            "turns them off once they gain little, the solver before session 6; slower on corridors).");
DEFINE_bool(
    ba_two_view_lines_apart, kDefaults.bundle_adjustment_options.two_view_lines_apart,
    "Bundle adjustment: leave the lines seen in exactly two views (not on the floor prior) out of the joint "
    "solves and solve each alone on their poses (they fit any poses exactly; same minimum, smaller solves).");
DEFINE_double(ba_loss_scale, kDefaults.bundle_adjustment_options.robust_loss_scale_px,
              "Bundle adjustment: scale (px) of the robust loss on image residuals.");
DEFINE_string(floor_prior, FloorPriorName(kDefaults.bundle_adjustment_options.floor_prior),
              "Bundle adjustment: ground-plane prior that fixes the odometry's scale: 'auto' (when the rig, the "
              "odometry and the map show a ground robot with its base origin on the floor), 'on' (whenever a floor "
              "plane is found) or 'off'.");
DEFINE_bool(floor_base_prior, kDefaults.bundle_adjustment_options.floor_base_prior,
            "Bundle adjustment: with the floor prior applied and the odometry on the floor plane, also hold every "
            "base pose's height and tilt there (floor sigma, and floor sigma / camera height rad).");
DEFINE_bool(floor_rescale_start, kDefaults.bundle_adjustment_options.floor_rescale_start,
            "Bundle adjustment: with the floor prior applied, start its solves from the coarse map scaled so that "
            "the floor found on it is at z = 0 (and the odometry's scale factor to match).");
DEFINE_bool(floor_scale_line_search, kDefaults.bundle_adjustment_options.floor_scale_line_search,
            "Bundle adjustment: with the floor prior applied, after the last solve, a line search on the odometry's "
            "scale factor (three solves with it held, a parabola, a last solve at its minimum).");
DEFINE_bool(
    floor_scale_search_solve_centre, kDefaults.bundle_adjustment_options.floor_scale_search_solve_centre,
    "Bundle adjustment: with the floor scale's line search, solve its centre sample again with the scale "
    "held (before session 6) instead of taking the last solve's cost there.");
DEFINE_string(
    odometry_rotation_bias,
    kDefaults.bundle_adjustment_options.estimate_odometry_rotation_bias            ? "on"
    : kDefaults.bundle_adjustment_options.estimate_odometry_rotation_bias_on_floor ? "auto"
                                                                                   : "off",
    "Bundle adjustment: estimate the odometry's constant rotation increment per step jointly with the "
    "poses: 'on', 'off' or 'auto' (where the floor prior may apply: a ground robot's rig and planar "
    "odometry).");
DEFINE_int32(threads, kDefaults.bundle_adjustment_options.num_threads, "Threads for the bundle adjustment.");
DEFINE_string(retriangulate_refined, RetriangulateRefinedName(kDefaults.retriangulate_refined),
              "After the bundle adjustment, triangulate every track again on the refined poses: 'off', "
              "'structure' (the landmarks refined on the refined poses, held fixed) or 'full' (then a second "
              "bundle adjustment starting from the refined poses).");
DEFINE_string(
    retriangulated_landmarks,
    kDefaults.retriangulated_landmarks == sfm::RetriangulatedLandmarks::kAddNew ? "add" : "replace",
    "With --retriangulate_refined: 'add' (only landmarks of tracks that had none) or 'replace' (every "
    "landmark re-triangulated).");
DEFINE_bool(extend_tracks, kDefaults.extend_tracks,
            "Track extension: project every point landmark into the frames its track misses and join the one "
            "compatible junction inside its uncertainty gate, or merge the track it belongs to; by default inside "
            "the bundle adjustment, after its first fine solve (--extend_tracks_stage).");
DEFINE_string(extend_tracks_stage, "inside",
              "With --extend_tracks, where it runs: 'inside' (the bundle adjustment, after its fine solve, then "
              "two fine solves and an outlier round more), 'coarse' (inside it, on its coarse stage's poses, before its "
              "fine solves), 'structure' (after it; the changed landmarks refined on the refined poses "
              "held fixed) or 'resolve' (after it, then a second bundle adjustment of everything).");
DEFINE_bool(extend_tracks_merge, kDefaults.track_extension.merge_tracks,
            "Track extension: merge two tracks when a projection finds the other's junction.");
DEFINE_double(extend_tracks_pixel_sigma, kDefaults.track_extension.pixel_sigma_px,
              "Track extension: pixel noise of a junction location in the gate, pixels.");
DEFINE_double(extend_tracks_rotation_step, kDefaults.track_extension.rotation_step_rad,
              "Track extension: the refined poses' rotation error per frame (random walk) in the gate, radians.");
DEFINE_double(extend_tracks_max_gate_px, kDefaults.track_extension.max_gate_px,
              "Track extension: the largest gate radius, pixels (a wider gate is not searched).");
DEFINE_double(extend_tracks_max_angle_deg, kDefaults.track_extension.max_angle_deg,
              "Track extension: the largest angle between a junction segment and its predicted direction, degrees.");
DEFINE_bool(wireframe_ba_pose_error, kDefaults.triangulation.wireframe.pose_error_from_bundle_adjustment,
            "Wireframe selection: the pose error of the determination test from bundle adjustment's own pose "
            "covariance instead of the fixed random walk.");
DEFINE_double(wireframe_tolerance_m, kDefaults.triangulation.wireframe.tolerance_m,
              "Wireframe selection: an accuracy asked of the drawn map, metres (0: off): the least determined "
              "vertices are dropped until the predicted share within it is --wireframe_tolerance_share "
              "(docs/tracks_and_triangulation.md, \"An accuracy asked of the map\").");
DEFINE_double(wireframe_tolerance_share, kDefaults.triangulation.wireframe.tolerance_share,
              "Wireframe selection: the share of drawn vertices asked to be within --wireframe_tolerance_m.");
DEFINE_bool(wireframe_plane_noise, kDefaults.triangulation.wireframe.line_sigma_subtracts_plane_noise,
            "Wireframe selection: a line vertex's sigma subtracts the information its planes' own noise "
            "fakes (a line whose planes spread no more than that noise is undetermined).");
DEFINE_double(wireframe_far_end_at_point_px, kDefaults.triangulation.wireframe.far_end_at_point_px,
              "Wireframe selection: a line's far end is taken at a drawn junction point when its observed "
              "image lines lie within this many pixels of its projections (median over the views, across "
              "the lines; 0: off; docs/tracks_and_triangulation.md, \"Far ends at junction points\").");
DEFINE_double(wireframe_far_end_along_px, kDefaults.triangulation.wireframe.far_end_along_px,
              "Wireframe selection, --wireframe_far_end_at_point_px: the largest median distance, pixels, "
              "along the observed image lines between the point's projections and the far end-points.");
DEFINE_bool(wireframe_far_end_shares_vertex, kDefaults.triangulation.wireframe.far_end_shares_vertex,
            "Wireframe selection, --wireframe_far_end_at_point_px: the edge ends at the point's own vertex "
            "(false: at a vertex of its own at the point's position).");
DEFINE_int32(wireframe_line_end_along_sigma, kDefaults.triangulation.wireframe.line_end_along_sigma,
             "Wireframe selection, rule 2: a back-projected line end's sigma includes its position along "
             "the line (0: off; 1: a line's own end0; 2: end0 and end1; docs/tracks_and_triangulation.md, "
             "\"A line end's position along the line\").");
DEFINE_bool(wireframe_line_variance_factor, kDefaults.triangulation.wireframe.line_variance_factor,
            "Wireframe selection: a line's vertex sigmas scaled by sqrt(its chi2 / dof over the lines' "
            "typical one) when "
            "above 1 (docs/tracks_and_triangulation.md, \"A line's own variance factor\").");
DEFINE_bool(
    wireframe_point_variance_factor, kDefaults.triangulation.wireframe.point_variance_factor,
    "Wireframe selection: a point's sigma scaled by sqrt(its chi2 / dof over the points' typical one) when "
    "above 1 (docs/tracks_and_triangulation.md, \"A line's own variance factor\").");

namespace {

// Flags -> options; a one-line message for a flag value that is not one of the choices.
bool OptionsFromFlags(sfm::PipelineOptions* options, std::string* error) {
  options->sequence_dir = FLAGS_sequence;
  options->output_dir = FLAGS_output;
  options->show_progress = FLAGS_progress;
  if (!sfm::UndistortInterpolationFromFlags(&options->undistort_interpolation, error)) return false;
  options->undistort_full_view = sfm::UndistortViewFromFlags() == sfm::UndistortView::kFullView;
  if (!sfm::SegmentMethodFromFlags(&options->segments, error)) return false;
  sfm::SegmentBranchesFromFlags(&options->segments.fast);
  sfm::JunctionChoiceFromFlags(&options->junctions);
  if (!sfm::MatchingFromFlags(&options->junctions, &options->matching, error)) return false;
  sfm::MatchingRefineFromFlags(&options->matching);
  options->bundle_adjustment = FLAGS_bundle_adjustment;
  options->extend_tracks = FLAGS_extend_tracks;
  if (FLAGS_extend_tracks_stage == "inside") {
    options->extend_tracks_stage = sfm::TrackExtensionStage::kInAdjustment;
  } else if (FLAGS_extend_tracks_stage == "coarse") {
    options->extend_tracks_stage = sfm::TrackExtensionStage::kAfterCoarse;
  } else if (FLAGS_extend_tracks_stage == "structure") {
    options->extend_tracks_stage = sfm::TrackExtensionStage::kAfterStructure;
  } else if (FLAGS_extend_tracks_stage == "resolve") {
    options->extend_tracks_stage = sfm::TrackExtensionStage::kAfterResolve;
  } else {
    *error = "--extend_tracks_stage must be 'inside', 'coarse', 'structure' or 'resolve', not '" + FLAGS_extend_tracks_stage + "'";
    return false;
  }
  options->track_extension.pixel_sigma_px = FLAGS_extend_tracks_pixel_sigma;
  options->track_extension.merge_tracks = FLAGS_extend_tracks_merge;
  options->track_extension.rotation_step_rad = FLAGS_extend_tracks_rotation_step;
  options->track_extension.max_gate_px = FLAGS_extend_tracks_max_gate_px;
  options->track_extension.max_angle_deg = FLAGS_extend_tracks_max_angle_deg;
  options->bundle_adjustment_options.outlier_threshold_px = FLAGS_ba_outlier_threshold;
  options->bundle_adjustment_options.robust_loss_scale_px = FLAGS_ba_loss_scale;
  options->bundle_adjustment_options.observability_rounds = FLAGS_ba_observability_rounds;
  options->bundle_adjustment_options.num_threads = FLAGS_threads;
  options->bundle_adjustment_options.inner_iterations_poses = FLAGS_ba_inner_iterations_poses;
  options->bundle_adjustment_options.single_pose_block = FLAGS_ba_single_pose_block;
  options->bundle_adjustment_options.inner_iterations_throughout = FLAGS_ba_inner_iterations_throughout;
  options->bundle_adjustment_options.two_view_lines_apart = FLAGS_ba_two_view_lines_apart;
  options->triangulation.wireframe.pose_error_from_bundle_adjustment = FLAGS_wireframe_ba_pose_error;
  options->triangulation.wireframe.line_sigma_subtracts_plane_noise = FLAGS_wireframe_plane_noise;
  options->triangulation.wireframe.tolerance_m = FLAGS_wireframe_tolerance_m;
  options->triangulation.wireframe.tolerance_share = FLAGS_wireframe_tolerance_share;
  options->triangulation.wireframe.far_end_at_point_px = FLAGS_wireframe_far_end_at_point_px;
  options->triangulation.wireframe.far_end_along_px = FLAGS_wireframe_far_end_along_px;
  options->triangulation.wireframe.far_end_shares_vertex = FLAGS_wireframe_far_end_shares_vertex;
  options->triangulation.wireframe.line_variance_factor = FLAGS_wireframe_line_variance_factor;
  options->triangulation.wireframe.line_end_along_sigma = FLAGS_wireframe_line_end_along_sigma;
  options->triangulation.wireframe.point_variance_factor = FLAGS_wireframe_point_variance_factor;
  options->bundle_adjustment_options.floor_base_prior = FLAGS_floor_base_prior;
  options->bundle_adjustment_options.floor_rescale_start = FLAGS_floor_rescale_start;
  options->bundle_adjustment_options.floor_scale_line_search = FLAGS_floor_scale_line_search;
  options->bundle_adjustment_options.floor_scale_search_solve_centre = FLAGS_floor_scale_search_solve_centre;
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
  if (FLAGS_retriangulate_refined == "off") {
    options->retriangulate_refined = sfm::RetriangulateRefined::kOff;
  } else if (FLAGS_retriangulate_refined == "structure") {
    options->retriangulate_refined = sfm::RetriangulateRefined::kStructure;
  } else if (FLAGS_retriangulate_refined == "full") {
    options->retriangulate_refined = sfm::RetriangulateRefined::kFull;
  } else {
    *error = "--retriangulate_refined must be 'off', 'structure' or 'full', not '" +
             FLAGS_retriangulate_refined + "'";
    return false;
  }
  if (FLAGS_retriangulated_landmarks == "add" || FLAGS_retriangulated_landmarks == "replace") {
    options->retriangulated_landmarks = FLAGS_retriangulated_landmarks == "add"
                                            ? sfm::RetriangulatedLandmarks::kAddNew
                                            : sfm::RetriangulatedLandmarks::kReplace;
  } else {
    *error =
        "--retriangulated_landmarks must be 'add' or 'replace', not '" + FLAGS_retriangulated_landmarks + "'";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "junction-based structure from motion.\n"
      "  junction_sfm --sequence <sequence dir> --output <output dir> [flags]");
  gflags::SetVersionString("0.1.0");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

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
    std::fprintf(stderr, "junction_sfm: %s\n", check.message().c_str());
    return 2;
  }
  const sfm::Status status = sfm::RunPipeline(options);
  if (!status.ok()) {
    std::fprintf(stderr, "junction_sfm: %s\n", status.message().c_str());
    return 1;
  }
  return 0;
}

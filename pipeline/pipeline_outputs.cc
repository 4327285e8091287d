#include "pipeline/pipeline_outputs.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "backend/export/colmap_model.h"
#include "backend/export/ply_io.h"
#include "geometry/tum_io.h"
#include "frontend/junctions/junctions_json.h"
#include "frontend/matching/matches_csv.h"
#include "frontend/tracks/tracks_csv.h"
#include "util/atomic_file.h"
#include "util/json_format.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;

std::string FrameFileStem(int frame) {
  char stem[16];
  std::snprintf(stem, sizeof(stem), "%06d", frame);
  return stem;
}

std::vector<StampedPose> Stamped(const Sequence& sequence, const std::vector<Pose3>& poses) {
  std::vector<StampedPose> stamped;
  stamped.reserve(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) stamped.push_back({sequence.frames[i].timestamp, poses[i]});
  return stamped;
}

// Junction points are vertices; each 3D line segment is an edge from its junction point (where it
// has one, so edges meet at junctions) or its own first end, to its far end.
ReconstructedWireframe WireframeOf(const Landmarks& landmarks) {
  ReconstructedWireframe wireframe;
  for (const PointLandmark& point : landmarks.points) wireframe.vertices.push_back(point.position);
  for (const LineLandmark& line : landmarks.lines) {
    int first = line.point_landmark;
    if (first < 0) {
      first = static_cast<int>(wireframe.vertices.size());
      wireframe.vertices.push_back(line.end0);
    }
    int last = line.end1_point_landmark;  // the far end at a drawn point shares its vertex
    if (last < 0) {
      last = static_cast<int>(wireframe.vertices.size());
      wireframe.vertices.push_back(line.end1);
    }
    wireframe.edges.emplace_back(first, last);
  }
  return wireframe;
}

ColmapModel ColmapModelOf(const Sequence& sequence, const std::vector<Pose3>& world_T_camera,
                          const Landmarks& landmarks) {
  ColmapModel model;
  model.camera = sequence.calibration.camera;
  for (size_t i = 0; i < world_T_camera.size(); ++i) {
    model.images.push_back({sequence.frames[i].image_path, world_T_camera[i]});
  }
  for (const PointLandmark& point : landmarks.points) {
    ColmapPoint colmap_point;
    colmap_point.position = point.position;
    for (const PointObservation& observation : point.observations) {
      colmap_point.track.push_back({observation.frame, observation.pixel});
    }
    model.points.push_back(std::move(colmap_point));
  }
  return model;
}

template <typename T, typename Count>
std::string JsonCountList(const std::vector<T>& items, Count count) {
  std::string list = "[";
  for (size_t i = 0; i < items.size(); ++i) list += (i ? ", " : "") + std::to_string(count(items[i]));
  return list + "]";
}

std::string RpeJson(const std::optional<DriftMetrics>& drift) {
  if (!drift) return "null";
  return "{\"trans_m\": " + JsonNumber(drift->rpe_trans_m) + ", \"rot_rad\": " + JsonNumber(drift->rpe_rot_rad) + "}";
}

// Not in SPEC's list (extra keys are allowed): whether the bundle adjustment's floor prior was
// used, the landmarks it held in the last solve, the floor's height when first found (before
// the prior moved it; null when none was found) and the odometry's scale factor it gave.
std::string FloorPriorJson(const PipelineResult& result, bool refined) {
  if (!refined) return "null";
  const BundleAdjustmentSummary& summary = result.bundle_adjustment;
  return "{\"used\": " + std::string(summary.floor_prior_used ? "true" : "false") +
         ", \"points\": " + std::to_string(summary.floor_points) + ", \"lines\": " + std::to_string(summary.floor_lines) +
         ", \"plane_z_m\": " + JsonNumber(summary.floor_plane_z_m) +
         ", \"odometry_scale\": " + JsonNumber(summary.odometry_scale) +
         ", \"report\": " + JsonString(summary.floor_prior_report) + "}";
}

// Not in SPEC's list: the odometry's rotation bias per step the bundle adjustment estimated
// ([x, y, z] rad, angle-axis in the base frame); null without bundle adjustment or when it was
// not estimated (--odometry_rotation_bias=off).
std::string RotationBiasJson(const PipelineResult& result, bool refined) {
  if (!refined || !result.bundle_adjustment.odometry_rotation_bias_estimated) return "null";
  const std::array<double, 3>& b = result.bundle_adjustment.odometry_rotation_bias_rad;
  return "[" + JsonNumber(b[0]) + ", " + JsonNumber(b[1]) + ", " + JsonNumber(b[2]) + "]";
}

// Not in SPEC's list: how many landmarks wireframe.ply draws and why the others are left out.
std::string WireframeJson(const PipelineResult& result) {
  const WireframeSelectionReport& report = result.wireframe_selection;
  return "{\"points\": " + std::to_string(report.points_kept) +
         ", \"lines\": " + std::to_string(report.lines_kept) +
         ", \"pixel_sigma_px\": " + JsonNumber(report.pixel_sigma_px) +
         ", \"points_untestable\": " + std::to_string(report.points_untestable) +
         ", \"points_occlusion_untested\": " + std::to_string(report.points_occlusion_untested) +
         ", \"points_inconsistent\": " + std::to_string(report.points_inconsistent) +
         ", \"points_undetermined\": " + std::to_string(report.points_uncertain) +
         ", \"lines_untestable\": " + std::to_string(report.lines_untestable) +
         ", \"lines_inconsistent\": " + std::to_string(report.lines_inconsistent) +
         ", \"lines_undetermined\": " +
         std::to_string(report.lines_uncertain_end0 + report.lines_uncertain_end1) +
         ", \"lines_unbounded\": " + std::to_string(report.lines_unbounded) +
         ", \"points_beyond_tolerance\": " + std::to_string(report.points_beyond_tolerance) +
         ", \"lines_beyond_tolerance\": " + std::to_string(report.lines_beyond_tolerance) +
         ", \"predicted_share\": " + JsonNumber(report.predicted_share) +
         ", \"pose_error_model\": " + JsonString(report.pose_error_model) +
         ", \"pose_covariance_s\": " + JsonNumber(report.pose_covariance_seconds) + "}";
}

// Not in SPEC's list: what the re-triangulation on the refined poses added (null when it did not
// run, --retriangulate_refined=off); "second_adjustment": the poses are a second adjustment's.
std::string RetriangulationJson(const PipelineResult& result) {
  const RetriangulationSummary& summary = result.retriangulation;
  if (!summary.ran) return "null";
  return "{\"points_added\": " + std::to_string(summary.points_added) +
         ", \"lines_added\": " + std::to_string(summary.lines_added) +
         ", \"observations_removed\": " + std::to_string(summary.observations_removed) +
         ", \"second_adjustment\": " + (summary.second_adjustment ? "true" : "false") + "}";
}

// Not in SPEC's list: what the track extension did (null when it did not run, --extend_tracks=false).
std::string TrackExtensionJson(const PipelineResult& result) {
  const TrackExtensionSummary& summary = result.track_extension;
  if (!summary.ran) return "null";
  return "{\"observations_added\": " + std::to_string(summary.observations_added) +
         ", \"tracks_merged\": " + std::to_string(summary.tracks_merged) +
         ", \"ambiguous\": " + std::to_string(summary.ambiguous) +
         ", \"observations_removed\": " + std::to_string(summary.observations_removed) +
         ", \"points_changed\": " + std::to_string(summary.points_changed) +
         ", \"lines_changed\": " + std::to_string(summary.lines_changed) +
         ", \"second_adjustment\": " + (summary.second_adjustment ? "true" : "false") +
         ", \"time_s\": " + JsonNumber(summary.seconds) + "}";
}

std::optional<double> Ate(const std::optional<DriftMetrics>& drift) {
  return drift ? std::optional<double>(drift->ate_m) : std::nullopt;
}

std::optional<double> AteSim3(const std::optional<DriftMetrics>& drift) {
  return drift ? std::optional<double>(drift->ate_sim3_m) : std::nullopt;
}

std::optional<double> Sim3Scale(const std::optional<DriftMetrics>& drift) {
  return drift ? std::optional<double>(drift->sim3_scale) : std::nullopt;
}

}  // namespace

std::string MetricsJson(const Sequence& sequence, const PipelineResult& result) {
  const StageTimes& times = result.times;
  const bool refined = !result.world_T_camera_refined.empty();
  std::ostringstream json;
  json << "{\n"
       << "  \"frames\": " << sequence.frames.size() << ",\n"
       << "  \"junctions_per_frame\": "
       << JsonCountList(result.junctions, [](const Junctions& j) { return j.size(); }) << ",\n"
       << "  \"matches_per_pair\": "
       << JsonCountList(result.pairs, [](const FramePairMatches& p) { return p.matches.size(); }) << ",\n"
       << "  \"matched_pairs\": "
       << "[";
  for (size_t i = 0; i < result.pairs.size(); ++i) {
    json << (i ? ", " : "") << "[" << result.pairs[i].frame_a << ", " << result.pairs[i].frame_b << "]";
  }
  json << "],\n"
       << "  \"tracks\": " << result.tracks.size() << ",\n"
       << "  \"points3d\": " << result.landmarks.points.size() << ",\n"
       << "  \"lines3d\": " << result.landmarks.lines.size() << ",\n"
       << "  \"unobservable_lines\": " << result.unobservable_lines << ",\n"
       << "  \"ate_odometry_m\": " << JsonNumber(Ate(result.drift_odometry)) << ",\n"
       << "  \"ate_refined_m\": " << JsonNumber(refined ? Ate(result.drift_refined) : std::nullopt) << ",\n"
       << "  \"rpe_odometry\": " << RpeJson(result.drift_odometry) << ",\n"
       << "  \"rpe_refined\": " << RpeJson(refined ? result.drift_refined : std::nullopt) << ",\n"
       << "  \"ate_sim3_odometry_m\": " << JsonNumber(AteSim3(result.drift_odometry)) << ",\n"
       << "  \"ate_sim3_refined_m\": " << JsonNumber(refined ? AteSim3(result.drift_refined) : std::nullopt)
       << ",\n"
       << "  \"sim3_scale_odometry\": " << JsonNumber(Sim3Scale(result.drift_odometry)) << ",\n"
       << "  \"sim3_scale_refined\": " << JsonNumber(refined ? Sim3Scale(result.drift_refined) : std::nullopt)
       << ",\n"
       << "  \"time_s\": {\"frontend\": " << JsonNumber(times.frontend)
       << ", \"matching\": " << JsonNumber(times.matching) << ", \"backend\": " << JsonNumber(times.backend)
       << ", \"total\": " << JsonNumber(times.total) << "},\n"
       << "  \"floor_prior\": " << FloorPriorJson(result, refined) << ",\n"
       << "  \"odometry_rotation_bias_rad\": " << RotationBiasJson(result, refined) << ",\n"
       << "  \"retriangulation\": " << RetriangulationJson(result) << ",\n"
       << "  \"track_extension\": " << TrackExtensionJson(result) << ",\n"
       << "  \"wireframe\": " << WireframeJson(result) << "\n"
       << "}\n";
  return json.str();
}

Status WriteOutputs(const Sequence& sequence, const PipelineResult& result, const std::string& output_dir) {
  const fs::path out(output_dir);
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((out / "junctions").string()));
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((out / "matches").string()));
  const Camera& camera = sequence.calibration.camera;
  for (size_t i = 0; i < result.junctions.size(); ++i) {
    const std::string json = JunctionsToJson(static_cast<int>(i), sequence.frames[i].image_path, camera.width,
                                             camera.height, result.junctions[i]);
    SFM_RETURN_IF_ERROR(WriteFileAtomically((out / "junctions" / (FrameFileStem(i) + ".json")).string(), json));
  }
  for (const FramePairMatches& pair : result.pairs) {
    const std::string name = FrameFileStem(pair.frame_a) + "_" + FrameFileStem(pair.frame_b) + ".csv";
    SFM_RETURN_IF_ERROR(
        WriteFileAtomically((out / "matches" / name).string(), MatchesCsv(result.junctions[pair.frame_a], result.junctions[pair.frame_b], pair.matches)));
  }
  SFM_RETURN_IF_ERROR(
      WriteFileAtomically((out / "tracks.csv").string(), TracksCsv(result.tracks, result.junctions)));

  SFM_RETURN_IF_ERROR(WriteTumTrajectory((out / "trajectory_odometry.txt").string(),
                                         Stamped(sequence, result.world_T_camera_odometry)));
  if (!result.world_T_camera_refined.empty()) {
    SFM_RETURN_IF_ERROR(WriteTumTrajectory((out / "trajectory_refined.txt").string(),
                                           Stamped(sequence, result.world_T_camera_refined)));
  }
  if (result.world_T_camera_truth) {
    SFM_RETURN_IF_ERROR(WriteTumTrajectory((out / "trajectory_groundtruth.txt").string(),
                                           Stamped(sequence, *result.world_T_camera_truth)));
  }
  SFM_RETURN_IF_ERROR(WritePly((out / "wireframe.ply").string(), WireframeOf(result.wireframe_landmarks)));
  const std::vector<Pose3>& poses =
      result.world_T_camera_refined.empty() ? result.world_T_camera_odometry : result.world_T_camera_refined;
  SFM_RETURN_IF_ERROR(WriteColmapModel((out / "colmap").string(), ColmapModelOf(sequence, poses, result.landmarks)));
  return WriteFileAtomically((out / "metrics.json").string(), MetricsJson(sequence, result));
}

}  // namespace sfm

#include "pipeline/pipeline_outputs.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "backend/export/colmap_model.h"
#include "backend/export/ply_io.h"
#include "frontend/junctions/junctions_json.h"
#include "frontend/matching/matches_csv.h"
#include "frontend/tracks/tracks_csv.h"
#include "geometry/tum_io.h"
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
// has one, so edges meet at junctions) or its own first end, through the points lying on it, to its
// far end (its far end's point where it has one); each edge between two points that the images show
// joined (Landmarks::point_edges) is an edge between their vertices.
ReconstructedWireframe WireframeOf(const Landmarks& landmarks) {
  ReconstructedWireframe wireframe;
  for (const PointLandmark& point : landmarks.points) {
    wireframe.vertices.push_back(point.position);
    wireframe.track_ids.push_back(point.track_id);
  }
  for (const LineLandmark& line : landmarks.lines) {
    int first = line.point_landmark;
    if (first < 0) {
      first = static_cast<int>(wireframe.vertices.size());
      wireframe.vertices.push_back(line.end0);
      wireframe.track_ids.push_back(-1);
    }
    int last = line.end1_point;
    if (last < 0) {
      last = static_cast<int>(wireframe.vertices.size());
      wireframe.vertices.push_back(line.end1);
      wireframe.track_ids.push_back(-1);
    }
    for (const int point : line.interior_points) {
      wireframe.edges.emplace_back(first, point);
      first = point;
    }
    wireframe.edges.emplace_back(first, last);
  }
  for (const auto& [a, b] : landmarks.point_edges) wireframe.edges.emplace_back(a, b);
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
  // POINT3D_ID = track_id + 1 (COLMAP's ids start at 1), the link from wireframe.ply's track_id,
  // when every point has a track (else the writer's index + 1).
  const bool tracked = std::all_of(landmarks.points.begin(), landmarks.points.end(),
                                   [](const PointLandmark& point) { return point.track_id >= 0; });
  for (size_t i = 0; tracked && i < model.points.size(); ++i)
    model.points[i].id = landmarks.points[i].track_id + 1;
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
  const TopologyEdgeReport& edges = result.topology_edges;
  return "{\"points\": " + std::to_string(report.points_kept) +
         ", \"lines\": " + std::to_string(result.wireframe_landmarks.lines.size()) +
         ", \"point_edges\": " + std::to_string(result.wireframe_landmarks.point_edges.size()) +
         ", \"point_edge_candidates\": " + std::to_string(edges.candidates) +
         ", \"point_edges_unsupported\": " + std::to_string(edges.unsupported) +
         ", \"point_edges_undetermined\": " + std::to_string(edges.undetermined) +
         ", \"point_edge_splits\": " + std::to_string(edges.splits) +
         ", \"lines_on_point_edges\": " + std::to_string(edges.lines_dropped) +
         ", \"manhattan_lines\": " + std::to_string(result.manhattan_lines.placed) +
         ", \"manhattan_leaving_view\": " + std::to_string(result.manhattan_lines.leaving_view) +
         ", \"manhattan_support\": " + JsonNumber(result.manhattan_lines.directions.support) +
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
         ", \"predicted_share\": " + JsonNumber(report.predicted_share) + "}";
}

// Not in SPEC's list: what the track extension did (null when it did not run, --extend_tracks=false).
std::string TrackExtensionJson(const PipelineResult& result) {
  const TrackExtensionSummary& summary = result.track_extension;
  if (!summary.ran) return "null";
  return "{\"points_triangulated_again\": " + std::to_string(summary.points_triangulated_again) +
         ", \"observations_added\": " + std::to_string(summary.observations_added) +
         ", \"tracks_merged\": " + std::to_string(summary.tracks_merged) +
         ", \"ambiguous\": " + std::to_string(summary.ambiguous) +
         ", \"points_changed\": " + std::to_string(summary.points_changed) +
         ", \"lines_changed\": " + std::to_string(summary.lines_changed) +
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

// [a, b, inliers] of each closed loop, comma separated.
std::string LoopsJson(const std::vector<std::array<int, 3>>& loops) {
  std::string json;
  for (size_t i = 0; i < loops.size(); ++i) {
    json += (i ? ", [" : "[") + std::to_string(loops[i][0]) + ", " + std::to_string(loops[i][1]) + ", " +
            std::to_string(loops[i][2]) + "]";
  }
  return json;
}

std::string InitializationJson(const PipelineResult& result) {
  const InitializationSummary& summary = result.initialization;
  if (!summary.ran) return "null";
  const VisualConstraintCounts& pairs = summary.pairs;
  const OdometryRotationEstimate& rotation = summary.rotation;
  const OdometryTranslationEstimate& translation = summary.translation;
  std::ostringstream json;
  json << "{\"pairs\": " << pairs.pairs << ", \"pairs_with_pose\": " << pairs.constraints
       << ", \"pairs_without_pose\": {\"too_few_matches\": " << pairs.too_few_matches
       << ", \"too_few_inliers\": " << pairs.too_few_inliers
       << ", \"beyond_odometry_gate\": " << pairs.inconsistent_with_prior
       << ", \"matches_add_nothing\": " << pairs.no_information << "}"
       << ", \"odometry_noise_declared\": {\"translation_sigma\": " << JsonNumber(summary.declared.translation_sigma)
       << ", \"rotation_sigma_rad\": " << JsonNumber(summary.declared.rotation_sigma) << "}"
       << ", \"odometry_noise_used\": {\"translation_sigma\": " << JsonNumber(summary.used.translation_sigma)
       << ", \"rotation_sigma_rad\": " << JsonNumber(summary.used.rotation_sigma) << "}"
       << ", \"odometry_rotation_measured\": "
       << (rotation.valid ? "{\"pairs\": " + std::to_string(rotation.steps) +
                                ", \"sigma_rad\": " + JsonNumber(rotation.sigma) + ", \"bias_rad\": [" +
                                JsonNumber(rotation.bias.x()) + ", " + JsonNumber(rotation.bias.y()) + ", " +
                                JsonNumber(rotation.bias.z()) + "]}"
                          : std::string("null"))
       << ", \"odometry_translation_measured\": "
       << (translation.valid ? "{\"steps\": " + std::to_string(translation.steps) +
                                   ", \"scale_error\": " + JsonNumber(translation.scale_error) +
                                   ", \"distance_sigma\": " + JsonNumber(translation.distance_sigma) + "}"
                             : std::string("null"))
       << ", \"rematched\": " << (summary.rematched ? "true" : "false")
       << ", \"pairs_recentred\": " << summary.recentred_pairs
       << ", \"pairs_rematched_after_adjustment\": " << summary.pairs_rematched_after_adjustment
       << ", \"loops\": {\"candidates\": " << summary.loop_candidates << ", \"closed\": [" << LoopsJson(summary.loops)
       << "]}"
       << ", \"pose_graph\": {\"constraints\": " << summary.pose_graph.constraints
       << ", \"constraints_beyond_3_sigma\": " << summary.pose_graph.constraints_rejected
       << ", \"iterations\": " << summary.pose_graph.iterations << "}"
       << ", \"time_s\": " << JsonNumber(summary.seconds) << "}";
  return json.str();
}

std::string EvidenceJson(const PipelineResult& result) {
  const TrajectoryEvidence& evidence = result.evidence;
  if (!evidence.computed) return "null";
  std::string frames;
  for (size_t i = 0; i < evidence.frames_disagreeing_with_odometry.size(); ++i) {
    frames += (i ? ", " : "") + std::to_string(evidence.frames_disagreeing_with_odometry[i]);
  }
  std::string warnings;
  for (size_t i = 0; i < evidence.warnings.size(); ++i) warnings += (i ? ", " : "") + JsonString(evidence.warnings[i]);
  return "{\"epipolar_px\": {\"odometry\": " + JsonNumber(evidence.epipolar_px_odometry) +
         ", \"initial\": " + JsonNumber(evidence.epipolar_px_initial) +
         ", \"refined\": " + JsonNumber(evidence.epipolar_px_refined) + "}" +
         ", \"frames_disagreeing_with_odometry\": [" + frames + "]" +
         ", \"refined_worse_than_odometry\": " + (evidence.refined_worse_than_odometry ? "true" : "false") +
         ", \"reprojection_rms_px\": {\"points\": " + JsonNumber(evidence.point_rms_px) +
         ", \"lines\": " + JsonNumber(evidence.line_rms_px) + "}" +
         ", \"adjustment_converged\": " + (evidence.adjustment_converged ? "true" : "false") +
         ", \"pair_inliers\": " + JsonCountList(evidence.pair_inliers, [](int n) { return n; }) +
         ", \"moved_from_odometry_m\": {\"median\": " + JsonNumber(evidence.moved_from_odometry_median_m) +
         ", \"max\": " + JsonNumber(evidence.moved_from_odometry_max_m) + "}" +
         ", \"moved_by_adjustment_max_m\": " + JsonNumber(evidence.moved_by_adjustment_max_m) +
         ", \"warnings\": [" + warnings + "]}";
}

}  // namespace

std::vector<std::string> OutputEntryNames() {
  return {"junctions",
          "matches",
          "tracks.csv",
          "trajectory_odometry.txt",
          "trajectory_refined.txt",
          "trajectory_groundtruth.txt",
          "wireframe.ply",
          "colmap",
          "metrics.json",
          "report.html",
          kLogFileName};
}

Status CheckOutputNames(const Sequence& sequence) {
  const std::string images_txt = (fs::path(sequence.directory) / "images.txt").string();
  for (const Frame& frame : sequence.frames) {
    const std::string which =
        images_txt + ": frame " + std::to_string(frame.index) + " ('" + frame.image_path + "')";
    if (!IsColmapImageName(frame.image_path)) {
      return Status::Error(which +
                           ": the image path holds white space, which colmap/images.txt cannot hold "
                           "(COLMAP splits its lines at spaces); rename the image");
    }
    if (!IsValidUtf8(frame.image_path)) {
      return Status::Error(images_txt + ": frame " + std::to_string(frame.index) +
                           ": the image path is not valid UTF-8, which the junction JSON cannot hold");
    }
  }
  return Status::Ok();
}

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
       << "  \"ate_initial_m\": " << JsonNumber(Ate(result.drift_initial)) << ",\n"
       << "  \"ate_sim3_initial_m\": " << JsonNumber(AteSim3(result.drift_initial)) << ",\n"
       << "  \"sim3_scale_odometry\": " << JsonNumber(Sim3Scale(result.drift_odometry)) << ",\n"
       << "  \"sim3_scale_refined\": " << JsonNumber(refined ? Sim3Scale(result.drift_refined) : std::nullopt)
       << ",\n"
       << "  \"time_s\": {\"frontend\": " << JsonNumber(times.frontend)
       << ", \"matching\": " << JsonNumber(times.matching) << ", \"backend\": " << JsonNumber(times.backend)
       << ", \"total\": " << JsonNumber(times.total) << "},\n"
       << "  \"initialization\": " << InitializationJson(result) << ",\n"
       << "  \"evidence\": " << EvidenceJson(result) << ",\n"
       << "  \"floor_prior\": " << FloorPriorJson(result, refined) << ",\n"
       << "  \"odometry_rotation_bias_rad\": " << RotationBiasJson(result, refined) << ",\n"
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
  // The poses the landmarks were made on: the refined ones, or without the bundle adjustment the
  // initial trajectory they were triangulated on.
  const std::vector<Pose3>& poses = !result.world_T_camera_refined.empty() ? result.world_T_camera_refined
                                    : !result.world_T_camera_initial.empty() ? result.world_T_camera_initial
                                                                             : result.world_T_camera_odometry;
  SFM_RETURN_IF_ERROR(WriteColmapModel((out / "colmap").string(), ColmapModelOf(sequence, poses, result.landmarks)));
  return WriteFileAtomically((out / "metrics.json").string(), MetricsJson(sequence, result));
}

}  // namespace sfm

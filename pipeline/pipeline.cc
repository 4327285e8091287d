#include "pipeline/pipeline.h"

#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjuster.h"
#include "backend/bundle_adjustment/pose_covariance.h"
#include "backend/metrics/drift.h"
#include "backend/triangulation/triangulate_tracks.h"
#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/pair_geometry.h"
#include "frontend/segments/undistorted_segments.h"
#include "frontend/sequence/sequence.h"
#include "frontend/tracks/tracks.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "pipeline/pipeline_outputs.h"
#include "pipeline/report/report.h"

namespace sfm {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Status LoadImages(const Sequence& sequence, Progress* progress, std::vector<cv::Mat>* images) {
  const int n = static_cast<int>(sequence.frames.size());
  images->resize(n);
  for (int i = 0; i < n; ++i) {
    progress->Update("reading images", "frame", i + 1, n);
    SFM_RETURN_IF_ERROR(LoadFrameImage(sequence, i, &(*images)[i]));
  }
  progress->Finish();
  return Status::Ok();
}

// What the frames are undistorted onto (PipelineOptions::undistort_full_view).
UndistortView DetectionView(const PipelineOptions& options) {
  return options.undistort_full_view ? UndistortView::kFullView : UndistortView::kSameSize;
}

// The box of K's pixel frame where junctions are detected, for the track extension: the image,
// or with options.undistort_full_view the full-view canvas that ImageUndistorter uses (without its
// pad), when the lens admits one (DetectionCanvas).
void DetectionBox(const Camera& camera, const PipelineOptions& options, Eigen::Vector2d* min,
                  Eigen::Vector2d* max) {
  Eigen::Vector2d offset;
  cv::Size size;
  DetectionCanvas(camera, DetectionView(options), 0, &offset, &size);
  *min = -offset;
  *max = Eigen::Vector2d(size.width - 1, size.height - 1) - offset;
}

// Paper section 2: junctions and topology graph of every frame, in undistorted pixels.
void DetectJunctionsOfAllFrames(const Sequence& sequence, const std::vector<cv::Mat>& images,
                                const PipelineOptions& options, Progress* progress, PipelineResult* result) {
  const ImageUndistorter undistorter(sequence.calibration.camera, options.undistort_interpolation,
                                     DetectionView(options));
  const int n = static_cast<int>(images.size());
  result->junctions.resize(n);
  result->graphs.resize(n);
  for (int i = 0; i < n; ++i) {
    progress->Update("junction detection", "frame", i + 1, n);
    const LineSegments segments = DetectUndistortedSegments(undistorter, images[i], options.segments);
    result->junctions[i] = DetectJunctions(segments, options.junctions);
    result->graphs[i] = BuildTopologyGraph(result->junctions[i]);
  }
  progress->Finish();
}

// F and its uncertainty for every pair to match (every consecutive pair and every pair two apart,
// so a junction missed in one frame does not break its track), from the calibration, the two
// odometry poses and the noise model of sequence.yaml. Part of the input's validation: finite but
// absurd odometry (a coordinate of 1e160) overflows here, and the matcher must not see it.
Status OdometryPairGeometries(const Sequence& sequence, const std::string& sequence_dir,
                              std::vector<std::pair<int, int>>* pairs,
                              std::vector<PairGeometry>* geometries) {
  const Calibration& calibration = sequence.calibration;
  *pairs = FramePairsToMatch(static_cast<int>(sequence.frames.size()));
  geometries->clear();
  geometries->reserve(pairs->size());
  for (const auto& [a, b] : *pairs) {
    PairGeometry geometry = PairGeometryFromOdometry(
        calibration.camera.K(), calibration.base_T_camera, sequence.frames[a].world_T_base_odometry,
        sequence.frames[b].world_T_base_odometry, calibration.odometry_noise.translation_sigma,
        calibration.odometry_noise.rotation_sigma, b - a);
    if (!(geometry.camera2_T_camera1.translation.allFinite() && geometry.covariance.allFinite())) {
      return Status::Error((std::filesystem::path(sequence_dir) / "odometry.txt").string() +
                           ": the poses of frames " + std::to_string(a) + " and " + std::to_string(b) +
                           " give no finite relative motion (coordinates too large?)");
    }
    geometries->push_back(geometry);
  }
  return Status::Ok();
}

// Paper sections 3-4 on the pairs of OdometryPairGeometries, with their geometry.
void MatchFramePairs(const std::vector<std::pair<int, int>>& pairs,
                     const std::vector<PairGeometry>& geometries, const PipelineOptions& options,
                     Progress* progress, PipelineResult* result) {
  for (size_t p = 0; p < pairs.size(); ++p) {
    progress->Update("matching", "pair", static_cast<int>(p) + 1, static_cast<int>(pairs.size()));
    const auto [a, b] = pairs[p];
    FramePairMatches matches;
    matches.frame_a = a;
    matches.frame_b = b;
    matches.matches = MatchJunctions(result->junctions[a], result->graphs[a], result->junctions[b],
                                     result->graphs[b], geometries[p], options.matching);
    result->pairs.push_back(std::move(matches));
  }
  progress->Finish();
}

// world_T_base of every frame's odometry.
std::vector<Pose3> OdometryBasePoses(const Sequence& sequence) {
  std::vector<Pose3> poses;
  poses.reserve(sequence.frames.size());
  for (const Frame& frame : sequence.frames) poses.push_back(frame.world_T_base_odometry);
  return poses;
}

// world_T_camera from world_T_base and back, with the rig's base_T_camera.
std::vector<Pose3> CamerasFromBases(const std::vector<Pose3>& world_T_base, const Pose3& base_T_camera) {
  std::vector<Pose3> cameras;
  cameras.reserve(world_T_base.size());
  for (const Pose3& pose : world_T_base) cameras.push_back(pose * base_T_camera);
  return cameras;
}
std::vector<Pose3> BasesFromCameras(const std::vector<Pose3>& world_T_camera, const Pose3& base_T_camera) {
  return CamerasFromBases(world_T_camera, base_T_camera.Inverse());
}

std::vector<Pose3> CameraPoses(const Sequence& sequence, bool groundtruth) {
  std::vector<Pose3> poses;
  poses.reserve(sequence.frames.size());
  for (const Frame& frame : sequence.frames) {
    const Pose3& world_T_base = groundtruth ? *frame.world_T_base_groundtruth : frame.world_T_base_odometry;
    poses.push_back(world_T_base * sequence.calibration.base_T_camera);
  }
  return poses;
}

// Tracks, then 3D points and lines from the odometry poses.
void Reconstruct(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  TrackBuildReport track_report;
  result->tracks = BuildTracks(result->junctions, result->pairs, &track_report);
  LOG(INFO) << "tracks: " << result->tracks.size() << " from " << track_report.matches << " matches ("
            << track_report.rejected_junction_conflict + track_report.rejected_segment_conflict
            << " rejected as inconsistent, " << track_report.skipped_partial_occlusion
            << " partial matches at a T or X not joined)";
  TriangulationReport triangulation_report;
  result->landmarks = TriangulateTracks(sequence.calibration.camera.K(), result->world_T_camera_odometry,
                                        result->junctions, result->tracks, options.triangulation,
                                        &triangulation_report);
  result->unobservable_lines = triangulation_report.Count(LineStatus::kUnobservable);
  LOG(INFO) << "triangulated " << result->landmarks.points.size() << " points and "
            << result->landmarks.lines.size() << " lines (" << result->unobservable_lines
            << " lines unobservable: parallel to the motion)";
}

// With --v=1: every landmark the floor prior held, with its junction types, for the diagnosis of
// the odometry scale it gives (docs/backend_results.md, "Session 4").
void LogFloorLandmarks(const std::string& stage, const PipelineResult& result) {
  if (!VLOG_IS_ON(1)) return;
  const BundleAdjustmentSummary& summary = result.bundle_adjustment;
  auto types = [&](const auto& observations) {
    std::string text;
    for (const auto& observation : observations) {
      text += JunctionTypeName(result.junctions[observation.frame][observation.junction].type);
      text += observation.frame == observations.back().frame ? "" : ",";
    }
    return text;
  };
  for (int i : summary.floor_point_indices) {
    const PointLandmark& point = result.landmarks.points[i];
    VLOG(1) << "floor " << stage << " point track " << point.track_id << " at " << point.position.transpose()
            << " views " << point.observations.size() << " first " << point.observations.front().frame
            << " types " << types(point.observations);
  }
  for (int i : summary.floor_line_indices) {
    const LineLandmark& line = result.landmarks.lines[i];
    const LineObservation& first = line.observations.front();
    VLOG(1) << "floor " << stage << " line " << first.frame << "/" << first.junction << "/" << first.segment
            << " from " << line.end0.transpose() << " to " << line.end1.transpose() << " views "
            << line.observations.size() << " types " << types(line.observations);
  }
}

// The track extension's counts into the result and the log.
void RecordTrackExtension(const TrackExtensionReport& report, Clock::time_point start, PipelineResult* result) {
  TrackExtensionSummary& summary = result->track_extension;
  summary.ran = true;
  summary.observations_added = report.observations_added;
  summary.tracks_merged = report.tracks_merged;
  summary.ambiguous = report.ambiguous;
  summary.points_changed = static_cast<int>(report.changed_points.size());
  summary.lines_changed = static_cast<int>(report.changed_lines.size());
  summary.seconds = SecondsSince(start);
  LOG(INFO) << "track extension: " << report.observations_added << " observations added, "
            << report.tracks_merged << " tracks merged (" << report.merges_refused << " refused), "
            << report.ambiguous << " ambiguous projections, " << report.gate_too_wide << " gates too wide, "
            << report.no_junction << " empty, " << report.incompatible
            << " with no compatible junction; refused merges: " << report.merge_overlap << " sharing a frame, "
            << report.merge_disagree << " disagreeing points, " << report.merge_unexplained << " not explained by the point; " << summary.points_changed << " points and "
            << summary.lines_changed << " lines changed; now " << result->tracks.size() << " tracks; "
            << summary.seconds << " s";
}

// Bundle adjustment from the odometry: refined poses and landmarks.
Status Refine(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  std::vector<Pose3> world_T_base_refined;
  BundleAdjustmentSummary summary;
  MapHook extend;
  if (options.extend_tracks && (options.extend_tracks_stage == TrackExtensionStage::kInAdjustment ||
                                options.extend_tracks_stage == TrackExtensionStage::kAfterCoarse)) {
    // The track extension inside the adjustment; its later solves refine what it changed.
    extend.when = options.extend_tracks_stage == TrackExtensionStage::kAfterCoarse ? MapHook::kAfterCoarse
                                                                                  : MapHook::kAfterFine;
    extend.change = [&](const std::vector<Pose3>& world_T_base, Landmarks* landmarks) {
      const Clock::time_point start = Clock::now();
      const Calibration& calibration = sequence.calibration;
      TrackExtensionReport report;
      Eigen::Vector2d box_min, box_max;
      DetectionBox(calibration.camera, options, &box_min, &box_max);
      ExtendTracks(calibration.camera.K(), box_min, box_max,
                   CamerasFromBases(world_T_base, calibration.base_T_camera), result->junctions,
                   options.track_extension, &result->tracks, landmarks, &report);
      RecordTrackExtension(report, start, result);
    };
  }
  SFM_RETURN_IF_ERROR(BundleAdjust(sequence.calibration, OdometryBasePoses(sequence),
                                   options.bundle_adjustment_options, &result->landmarks, &world_T_base_refined,
                                   &summary, extend));
  result->unobservable_lines += summary.lines_unobservable;
  result->bundle_adjustment = summary;
  result->world_T_camera_refined = CamerasFromBases(world_T_base_refined, sequence.calibration.base_T_camera);
  LOG(INFO) << "bundle adjustment: " << summary.points << " points, " << summary.lines << " lines, "
            << summary.observations << " observations; " << summary.observations_removed
            << " outlier observations removed, " << summary.lines_unobservable << " more lines unobservable ("
            << summary.landmarks_unobservable_after_last_solve << " landmarks after the last solve, "
            << summary.observability_solves << " solves more); "
            << "RMS " << summary.point_rms_px << " px (points), " << summary.line_rms_px << " px (lines); "
            << summary.solves << " solves, " << summary.iterations << " iterations, " << summary.time_s << " s; "
            << summary.solver_report;
  LOG(INFO) << summary.floor_prior_report
            << (summary.floor_prior_used ? "; odometry scale " + std::to_string(summary.odometry_scale) : "");
  LogFloorLandmarks("first", *result);
  return Status::Ok();
}

// A second bundle adjustment of the changed map (`what` says how, for the log), starting from the
// refined poses and the first adjustment's odometry scale; the odometry stays the prior. Its
// poses and summary replace the first's.
Status AdjustAgainFromRefinedPoses(const Sequence& sequence, const BundleAdjustmentOptions& bundle_options,
                                   const std::string& what, PipelineResult* result) {
  const Calibration& calibration = sequence.calibration;
  std::vector<Pose3> world_T_base_second;
  BundleAdjustmentSummary summary;
  SFM_RETURN_IF_ERROR(BundleAdjust(calibration, OdometryBasePoses(sequence),
                                   BasesFromCameras(result->world_T_camera_refined, calibration.base_T_camera),
                                   result->bundle_adjustment.odometry_scale, bundle_options, &result->landmarks,
                                   &world_T_base_second, &summary));
  result->bundle_adjustment = summary;
  result->world_T_camera_refined = CamerasFromBases(world_T_base_second, calibration.base_T_camera);
  LOG(INFO) << "second bundle adjustment " << what << ": " << summary.points << " points, " << summary.lines
            << " lines; " << summary.observations_removed << " outlier observations removed; RMS "
            << summary.point_rms_px << " px (points), " << summary.line_rms_px << " px (lines); "
            << summary.floor_prior_report
            << (summary.floor_prior_used ? "; odometry scale " + std::to_string(summary.odometry_scale) : "")
            << "; " << summary.solves << " solves, " << summary.iterations << " iterations, " << summary.time_s
            << " s";
  return Status::Ok();
}

// Every track triangulated again on the refined poses: tracks whose triangulation failed on the
// drifting odometry (parallax, reprojection) can pass now. The new landmarks are refined on the
// refined poses held fixed and pass the adjustment's outlier rules before they join the map
// (docs/tracks_and_triangulation.md, "Re-triangulation on the refined poses"). kFull then adjusts
// everything again, starting from the refined poses; the odometry stays the prior.
Status RetriangulateOnRefinedPoses(const Sequence& sequence, const PipelineOptions& options,
                                   PipelineResult* result) {
  const Calibration& calibration = sequence.calibration;
  const std::vector<Pose3> world_T_base_refined =
      BasesFromCameras(result->world_T_camera_refined, calibration.base_T_camera);
  TriangulationReport triangulation_report;
  Landmarks retriangulated =
      TriangulateTracks(calibration.camera.K(), result->world_T_camera_refined, result->junctions,
                        result->tracks, options.triangulation, &triangulation_report);
  const size_t triangulated_points = retriangulated.points.size(),
               triangulated_lines = retriangulated.lines.size();
  BundleAdjustmentSummary structure_summary;
  SFM_RETURN_IF_ERROR(RefineLandmarksOnFixedPoses(calibration, world_T_base_refined,
                                                  options.bundle_adjustment_options, &retriangulated,
                                                  &structure_summary));
  const size_t points_before = result->landmarks.points.size(), lines_before = result->landmarks.lines.size();
  LandmarkMergeReport merge;
  MergeRetriangulatedLandmarks(retriangulated, options.retriangulated_landmarks, &result->landmarks, &merge);
  result->retriangulation.ran = true;
  result->retriangulation.points_added = merge.points_added;
  result->retriangulation.lines_added = merge.lines_added;
  result->retriangulation.observations_removed = structure_summary.observations_removed;
  LOG(INFO) << "re-triangulation on the refined poses: " << triangulated_points << " points and "
            << triangulated_lines << " lines triangulated, " << retriangulated.points.size() << " and "
            << retriangulated.lines.size() << " kept after refining them on the fixed poses ("
            << structure_summary.observations_removed << " outlier observations removed); map "
            << points_before << " -> " << result->landmarks.points.size() << " points, " << lines_before
            << " -> " << result->landmarks.lines.size() << " lines (" << merge.lines_linked_to_existing_point
            << " new lines at an existing point)";
  if (options.retriangulate_refined != RetriangulateRefined::kFull) return Status::Ok();

  SFM_RETURN_IF_ERROR(AdjustAgainFromRefinedPoses(sequence, options.bundle_adjustment_options,
                                                  "from the refined poses", result));
  result->retriangulation.second_adjustment = true;
  LogFloorLandmarks("second", *result);
  return Status::Ok();
}

// Tracks extended and merged by projecting the adjusted points into the frames they miss
// (track_extension.h); the landmarks that gained observations are then refined alone on the
// refined poses held fixed, by the adjustment's outlier rules (RefineLandmarksOnFixedPoses), and
// replace their old selves. The trajectory is unchanged.
Status ExtendTracksOnRefinedPoses(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  const Clock::time_point start = Clock::now();
  const Calibration& calibration = sequence.calibration;
  TrackExtensionReport report;
  Eigen::Vector2d box_min, box_max;
  DetectionBox(calibration.camera, options, &box_min, &box_max);
  ExtendTracks(calibration.camera.K(), box_min, box_max, result->world_T_camera_refined, result->junctions,
               options.track_extension, &result->tracks, &result->landmarks, &report);
  // The changed landmarks as a map of their own (every changed line's point is changed too, or
  // joins it), refined, then put back after the unchanged ones.
  Landmarks& map = result->landmarks;
  std::vector<bool> point_in(map.points.size(), false), line_in(map.lines.size(), false);
  for (int p : report.changed_points) point_in[p] = true;
  for (int l : report.changed_lines) {
    line_in[l] = true;
    if (map.lines[l].point_landmark >= 0) point_in[map.lines[l].point_landmark] = true;
  }
  Landmarks changed, kept;
  std::vector<int> index_in(map.points.size(), -1);
  for (size_t p = 0; p < map.points.size(); ++p) {
    Landmarks& to = point_in[p] ? changed : kept;
    index_in[p] = static_cast<int>(to.points.size());
    to.points.push_back(std::move(map.points[p]));
  }
  for (size_t l = 0; l < map.lines.size(); ++l) {
    LineLandmark line = std::move(map.lines[l]);
    if (line.point_landmark >= 0) {
      CHECK(line_in[l] || !point_in[line.point_landmark]) << "a changed point's line left out";
      line.point_landmark = index_in[line.point_landmark];
    }
    (line_in[l] ? changed : kept).lines.push_back(std::move(line));
  }
  BundleAdjustmentSummary structure;
  SFM_RETURN_IF_ERROR(RefineLandmarksOnFixedPoses(
      calibration, BasesFromCameras(result->world_T_camera_refined, calibration.base_T_camera),
      options.bundle_adjustment_options, &changed, &structure));
  const int offset = static_cast<int>(kept.points.size());
  for (PointLandmark& point : changed.points) kept.points.push_back(std::move(point));
  for (LineLandmark& line : changed.lines) {
    if (line.point_landmark >= 0) line.point_landmark += offset;
    kept.lines.push_back(std::move(line));
  }
  map = std::move(kept);
  RecordTrackExtension(report, start, result);
  TrackExtensionSummary& summary = result->track_extension;
  summary.observations_removed = structure.observations_removed;
  summary.seconds = SecondsSince(start);
  LOG(INFO) << "track extension: the changed landmarks refined on the fixed poses, "
            << structure.observations_removed << " outlier observations removed; now " << map.points.size()
            << " points, " << map.lines.size() << " lines; " << summary.seconds << " s";
  if (options.extend_tracks_stage != TrackExtensionStage::kAfterResolve) return Status::Ok();

  // The first adjustment's line search already placed the odometry's scale, and the second starts
  // from it: its own search (three solves more) would only repeat it.
  BundleAdjustmentOptions second_options = options.bundle_adjustment_options;
  second_options.floor_scale_line_search = false;
  SFM_RETURN_IF_ERROR(AdjustAgainFromRefinedPoses(sequence, second_options, "on the extended tracks", result));
  summary.second_adjustment = true;
  summary.seconds = SecondsSince(start);
  LOG(INFO) << "track extension and its second adjustment: " << summary.seconds << " s";
  return Status::Ok();
}

// Bundle adjustment's own covariance of the refined poses, at the pixel noise the wireframe's tests
// use (docs/tracks_and_triangulation.md, "Pose error from bundle adjustment"); null when it cannot
// be computed (the wireframe then keeps the random-walk model). With ground truth, the log compares
// it with the refined trajectory's actual relative pose errors.
std::shared_ptr<const PoseCovariance> RefinedPoseCovariance(const Sequence& sequence,
                                                            const PipelineOptions& options,
                                                            const PipelineResult& result) {
  const WireframeOptions& wireframe = options.triangulation.wireframe;
  const Eigen::Matrix3d K = sequence.calibration.camera.K();
  const std::vector<Pose3>& poses = result.world_T_camera_refined;
  const double sigma_px =
      wireframe.estimate_pixel_sigma
          ? std::max(wireframe.pixel_sigma_px, EstimatePixelSigma(K, poses, result.landmarks))
          : wireframe.pixel_sigma_px;
  const std::vector<Pose3> odometry = OdometryBasePoses(sequence);
  const std::vector<Pose3> refined = BasesFromCameras(poses, sequence.calibration.base_T_camera);
  auto covariance = std::make_shared<PoseCovariance>();
  const Status status = ComputePoseCovariance(sequence.calibration, odometry, refined, result.landmarks,
                                              options.bundle_adjustment_options, sigma_px, covariance.get());
  if (!status.ok()) {
    LOG(WARNING) << status.message() << "; the wireframe keeps the random-walk pose error model";
    return nullptr;
  }
  if (result.world_T_camera_truth) {
    for (const PoseCovarianceCheck& check :
         CheckPoseCovariance(*covariance, poses, *result.world_T_camera_truth, {1, 4, 16, 32})) {
      LOG(INFO) << "pose covariance against the truth, lag " << check.lag << " (" << check.pairs
                << " pairs): rotation RMS predicted " << check.predicted_rotation_rad << " rad, actual "
                << check.actual_rotation_rad << "; centre predicted " << check.predicted_centre_m
                << " m, actual " << check.actual_centre_m;
    }
  }
  return covariance;
}

// The landmarks the wireframe draws (docs/tracks_and_triangulation.md, "Wireframe vertices"):
// judged on the final poses; bundle adjustment and the COLMAP model keep every landmark.
void SelectWireframe(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  const std::vector<Pose3>& poses =
      result->world_T_camera_refined.empty() ? result->world_T_camera_odometry : result->world_T_camera_refined;
  const WireframeOptions& wireframe = options.triangulation.wireframe;
  const Eigen::Matrix3d K = sequence.calibration.camera.K();
  PoseDrift drift = WireframePoseDrift(wireframe, poses);
  double covariance_seconds = 0;
  if (wireframe.pose_error_from_bundle_adjustment && !result->world_T_camera_refined.empty()) {
    const Clock::time_point start = Clock::now();
    drift.covariance = RefinedPoseCovariance(sequence, options, *result);
    covariance_seconds = SecondsSince(start);
  }
  WireframeSelectionReport& report = result->wireframe_selection;
  result->wireframe_landmarks =
      SelectWireframeLandmarks(K, poses, result->landmarks, result->junctions, wireframe, drift, &report);
  report.pose_error_model = drift.covariance ? "bundle_adjustment" : "random_walk";
  report.pose_covariance_seconds = covariance_seconds;
  LOG(INFO) << "wireframe: " << report.points_kept << " of " << result->landmarks.points.size()
            << " points and " << report.lines_kept << " of " << result->landmarks.lines.size()
            << " lines drawn (pixel noise " << report.pixel_sigma_px << " px); not drawn: points "
            << report.points_untestable << " untestable, " << report.points_occlusion_untested
            << " occlusion candidates with too few views, " << report.points_inconsistent << " inconsistent, "
            << report.points_uncertain << " undetermined; lines " << report.lines_untestable
            << " untestable, " << report.lines_inconsistent << " inconsistent, "
            << report.lines_uncertain_end0 + report.lines_uncertain_end1 << " undetermined, "
            << report.lines_unbounded << " unbounded; " << report.lines_far_end_at_point
            << " far ends at drawn points";
}

}  // namespace

Status PipelineOptions::Check() const {
  if (output_dir.empty()) return Status::Error("--output must name a directory");
  SFM_RETURN_IF_ERROR(segments.Check());
  SFM_RETURN_IF_ERROR(junctions.Check());
  SFM_RETURN_IF_ERROR(matching.Check());
  SFM_RETURN_IF_ERROR(triangulation.Check());
  if (extend_tracks) SFM_RETURN_IF_ERROR(track_extension.Check());
  return bundle_adjustment_options.Check();
}

Status RunPipeline(const PipelineOptions& options, PipelineResult* result_out) {
  const Clock::time_point start = Clock::now();
  SFM_RETURN_IF_ERROR(options.Check());

  // 1. Read and validate all input before anything is written.
  Sequence sequence;
  SFM_RETURN_IF_ERROR(ReadSequence(options.sequence_dir, &sequence));
  LOG(INFO) << "sequence " << options.sequence_dir << ": " << sequence.frames.size() << " frames, "
            << sequence.calibration.camera.width << "x" << sequence.calibration.camera.height
            << (sequence.has_groundtruth ? ", with ground truth" : ", no ground truth");
  Progress progress(options.show_progress);
  std::vector<cv::Mat> images;
  SFM_RETURN_IF_ERROR(LoadImages(sequence, &progress, &images));
  std::vector<std::pair<int, int>> pairs;
  std::vector<PairGeometry> pair_geometries;
  SFM_RETURN_IF_ERROR(OdometryPairGeometries(sequence, options.sequence_dir, &pairs, &pair_geometries));
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(options.output_dir));

  PipelineResult result;
  result.world_T_camera_odometry = CameraPoses(sequence, /*groundtruth=*/false);
  if (sequence.has_groundtruth) result.world_T_camera_truth = CameraPoses(sequence, /*groundtruth=*/true);

  // 2. Front end, matching, back end.
  Clock::time_point stage_start = Clock::now();
  DetectJunctionsOfAllFrames(sequence, images, options, &progress, &result);
  result.times.frontend = SecondsSince(stage_start);
  stage_start = Clock::now();
  MatchFramePairs(pairs, pair_geometries, options, &progress, &result);
  result.times.matching = SecondsSince(stage_start);
  stage_start = Clock::now();
  Reconstruct(sequence, options, &result);
  if (options.bundle_adjustment) {
    SFM_RETURN_IF_ERROR(Refine(sequence, options, &result));
    if (options.extend_tracks && (options.extend_tracks_stage == TrackExtensionStage::kAfterStructure ||
                                  options.extend_tracks_stage == TrackExtensionStage::kAfterResolve)) {
      SFM_RETURN_IF_ERROR(ExtendTracksOnRefinedPoses(sequence, options, &result));
    }
    if (options.retriangulate_refined != RetriangulateRefined::kOff) {
      SFM_RETURN_IF_ERROR(RetriangulateOnRefinedPoses(sequence, options, &result));
    }
  }
  SelectWireframe(sequence, options, &result);
  result.times.backend = SecondsSince(stage_start);
  if (result.world_T_camera_truth) {
    result.drift_odometry = ComputeDrift(result.world_T_camera_odometry, *result.world_T_camera_truth);
    if (!result.world_T_camera_refined.empty()) {
      result.drift_refined = ComputeDrift(result.world_T_camera_refined, *result.world_T_camera_truth);
    }
  }

  // 3. Outputs.
  result.times.total = SecondsSince(start);
  SFM_RETURN_IF_ERROR(WriteOutputs(sequence, result, options.output_dir));
  SFM_RETURN_IF_ERROR(WriteReport(sequence, result, /*undistorted_images_or_empty=*/{}, options.output_dir));
  LOG(INFO) << "time: frontend " << result.times.frontend << " s, matching " << result.times.matching
            << " s, backend " << result.times.backend << " s, total " << result.times.total << " s";
  if (result_out) *result_out = std::move(result);
  return Status::Ok();
}

}  // namespace sfm

#include "pipeline/pipeline.h"

#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjuster.h"
#include "backend/initialization/loop_candidates.h"
#include "backend/initialization/odometry_noise_estimate.h"
#include "backend/initialization/pose_graph.h"
#include "backend/initialization/trajectory_evidence.h"
#include "backend/initialization/visual_constraints.h"
#include "backend/metrics/drift.h"
#include "backend/triangulation/reconstruction.h"
#include "backend/triangulation/track_extension.h"
#include "backend/triangulation/triangulate_tracks.h"
#include "frontend/batch/sequence_frontend.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/pair_geometry.h"
#include "frontend/segments/undistorted_segments.h"
#include "frontend/sequence/sequence.h"
#include "frontend/tracks/tracks.h"
#include "geometry/image_undistorter.h"
#include "pipeline/pipeline_outputs.h"
#include "pipeline/report/report.h"
#include "util/atomic_file.h"
#include "util/parallel.h"
#include "util/progress.h"

namespace sfm {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The seconds of each stage of a run in order, for the log's last line; the running stage is shown
// on the progress line.
class StageTimer {
 public:
  explicit StageTimer(Progress* progress) : progress_(progress) {}
  // Ends the running stage, if any, and starts `name`.
  void Start(const std::string& name) {
    End();
    name_ = name;
    start_ = Clock::now();
    progress_->Show(name, "");
  }
  void End() {
    if (!name_.empty())
      text_ << (text_.tellp() > 0 ? ", " : "") << name_ << " " << SecondsSince(start_) << " s";
    name_.clear();
  }
  std::string Text() const { return text_.str(); }

 private:
  Progress* progress_;
  std::string name_;
  Clock::time_point start_;
  std::ostringstream text_;
};

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

// Paper section 2: junctions and topology graph of every frame, in undistorted pixels, the frames
// decoded one at a time per thread (DetectSequenceJunctions), and their keypoints for the pairs'
// pose hypotheses (KeypointPairPoses).
Status DetectJunctionsOfAllFrames(const Sequence& sequence, const PipelineOptions& options, Progress* progress,
                                  std::vector<FrameKeypoints>* keypoints, PipelineResult* result) {
  const ImageUndistorter undistorter(sequence.calibration.camera, options.undistort_interpolation,
                                     DetectionView(options));
  return DetectSequenceJunctions(sequence, undistorter, options.segments, options.junctions, progress,
                                 &result->junctions, &result->graphs, keypoints);
}

// F and its uncertainty of frames a and b from base poses world_T_base (the odometry's, or a
// trajectory's the noise is then centred on) with the odometry's noise model.
PairGeometry PairGeometryOnTrajectory(const Calibration& calibration, const std::vector<Pose3>& world_T_base,
                                      int a, int b, const OdometryNoise& noise) {
  return PairGeometryFromOdometry(calibration.camera.K(), calibration.base_T_camera, world_T_base[a], world_T_base[b],
                                  noise.translation_sigma, noise.rotation_sigma, b - a);
}

std::vector<Pose3> OdometryBasePoses(const Sequence& sequence);

// F and its uncertainty for every pair to match (every consecutive pair and every pair two apart,
// so a junction missed in one frame does not break its track), from the calibration, the two
// odometry poses and the noise model of sequence.yaml. Part of the input's validation: finite but
// absurd odometry (a coordinate of 1e160) overflows here, and the matcher must not see it.
Status OdometryPairGeometries(const Sequence& sequence, const std::string& sequence_dir,
                              const OdometryNoise& noise, std::vector<std::pair<int, int>>* pairs,
                              std::vector<PairGeometry>* geometries) {
  const std::vector<Pose3> odometry = OdometryBasePoses(sequence);
  *pairs = FramePairsToMatch(static_cast<int>(sequence.frames.size()));
  geometries->clear();
  geometries->reserve(pairs->size());
  for (const auto& [a, b] : *pairs) {
    const PairGeometry geometry = PairGeometryOnTrajectory(sequence.calibration, odometry, a, b, noise);
    if (!(geometry.camera2_T_camera1.translation.allFinite() && geometry.covariance.allFinite())) {
      return Status::Error((std::filesystem::path(sequence_dir) / "odometry.txt").string() +
                           ": the poses of frames " + std::to_string(a) + " and " + std::to_string(b) +
                           " give no finite relative motion (coordinates too large?)");
    }
    geometries->push_back(geometry);
  }
  return Status::Ok();
}

std::vector<Pose3> CamerasFromBases(const std::vector<Pose3>& world_T_base, const Pose3& base_T_camera);
std::vector<Pose3> BasesFromCameras(const std::vector<Pose3>& world_T_camera, const Pose3& base_T_camera);

// Radians: below this, the odometry's rotation noise on an axis is not told apart from the
// images' own (the spread of a pair's rotation from 20-100 junction matches).
constexpr double kImageRotationSigmaFloor = 2e-4;

// A run whose points reproject with an RMS beyond this many junction location sigmas is flagged
// as unreliable: the location noise alone gives about one.
constexpr double kUnreliableRmsLocationSigmas = 3;

// A loop pair needs this many times the inliers of any pair's pose (CloseLoops).
constexpr int kLoopInlierFactor = 2;

// A measured odometry rotation noise this many times the declared one widens the matcher's gates
// (MeasureOdometryNoise).
constexpr double kRematchNoiseFactor = 1.5;

// The odometry's rotation noise measured against the relative rotations the verified poses fit
// (docs/initialization.md, "Odometry noise from the data"). When the images say the odometry
// turns more erratically than declared, its gates were too narrow for the true matches: *rematch
// says the pairs are to be matched again with the measured noise. The pose graph and the bundle
// adjustment weigh the odometry by the measured noise in every case.
void MeasureOdometryNoise(const Sequence& sequence, const PipelineOptions& options,
                          const std::vector<std::pair<int, int>>& pairs,
                          const std::vector<MatchingDiagnostics>& diagnostics, bool* rematch, PipelineResult* result) {
  *rematch = false;
  InitializationSummary& summary = result->initialization;
  summary.ran = true;
  summary.declared = sequence.calibration.odometry_noise;
  summary.used = summary.declared;
  const Pose3& base_T_camera = sequence.calibration.base_T_camera;
  const std::vector<Pose3> odometry = OdometryBasePoses(sequence);
  summary.rotation = EstimateOdometryRotationNoise(
      odometry, base_T_camera, VisualRotationSamples(pairs, diagnostics, options.Matching().refine_min_inliers));
  if (!summary.rotation.valid) {
    LOG(INFO) << "odometry noise: too few image pairs with a relative pose (" << summary.rotation.steps
              << ") to measure it; the declared noise is used";
    return;
  }
  const double measured = summary.rotation.EffectiveSigma();
  LOG(INFO) << "odometry rotation noise from " << summary.rotation.steps << " image pairs: " << measured
            << " rad per frame (bias " << summary.rotation.bias.transpose() << ", spread " << summary.rotation.sigma
            << "); declared " << summary.declared.rotation_sigma;
  if (sequence.calibration.odometry_noise_given &&
      DeclaredSigmaContradicted(summary.declared.rotation_sigma, measured)) {
    LOG(WARNING) << options.sequence_dir << "/sequence.yaml: odometry_rotation_sigma " << summary.declared.rotation_sigma
                 << " rad per frame, but the images measure " << measured << "; the measured value is used";
  }
  summary.used.rotation_sigma = measured;
  *rematch = measured > kRematchNoiseFactor * summary.declared.rotation_sigma;
}

// VerifySequencePairs on the pairs whose `consecutive` (frame b = frame a + 1) is as given, into
// their places in `matches` and `diagnostics` (sized for every pair).
void VerifyPairsWhere(bool consecutive, const std::vector<std::pair<int, int>>& pairs,
                      const std::vector<PairGeometry>& geometries, const PipelineOptions& options,
                      Progress* progress, PipelineResult* result, std::vector<MatchingDiagnostics>* diagnostics) {
  std::vector<int> chosen;
  std::vector<std::pair<int, int>> chosen_pairs;
  std::vector<PairGeometry> chosen_geometries;
  for (size_t p = 0; p < pairs.size(); ++p) {
    if ((pairs[p].second == pairs[p].first + 1) != consecutive) continue;
    chosen.push_back(static_cast<int>(p));
    chosen_pairs.push_back(pairs[p]);
    chosen_geometries.push_back(geometries[p]);
  }
  std::vector<FramePairMatches> matches;
  std::vector<MatchingDiagnostics> chosen_diagnostics;
  VerifySequencePairs(chosen_pairs, chosen_geometries, result->junctions, result->graphs, options.Matching(),
                      progress, &matches, &chosen_diagnostics);
  for (size_t k = 0; k < chosen.size(); ++k) {
    result->pairs[chosen[k]] = std::move(matches[k]);
    (*diagnostics)[chosen[k]] = std::move(chosen_diagnostics[k]);
  }
}

// Paper sections 3-4 on the pairs of OdometryPairGeometries, with their geometry, in two steps:
// every pair's first pass and verified pose, then (MeasureOdometryNoise) every pair's guided pass,
// or, when the verified poses say the odometry's gates were too narrow, the whole matching again
// with wider ones. The noise is measured on consecutive pairs, so the other pairs' first pass runs
// only when it is kept. `diagnostics` receives each pair's refinement, in the order of `pairs`.
Status MatchFramePairs(const Sequence& sequence, const PipelineOptions& options,
                       const std::vector<std::pair<int, int>>& pairs,
                       const std::vector<KeypointCorrespondences>& keypoint_matches,
                       std::vector<PairGeometry>* geometries, Progress* progress,
                       std::vector<MatchingDiagnostics>* diagnostics, PipelineResult* result) {
  result->pairs.assign(pairs.size(), FramePairMatches());
  diagnostics->assign(pairs.size(), MatchingDiagnostics());
  VerifyPairsWhere(/*consecutive=*/true, pairs, *geometries, options, progress, result, diagnostics);
  bool rematch = false;
  MeasureOdometryNoise(sequence, options, pairs, *diagnostics, &rematch, result);
  result->initialization.rematched = rematch;
  if (rematch) {
    LOG(INFO) << "matching again with the measured odometry noise";
    std::vector<std::pair<int, int>> same_pairs;
    SFM_RETURN_IF_ERROR(OdometryPairGeometries(sequence, options.sequence_dir, result->initialization.used,
                                               &same_pairs, geometries));
  } else {
    VerifyPairsWhere(/*consecutive=*/false, pairs, *geometries, options, progress, result, diagnostics);
  }
  const std::vector<std::optional<Pose3>> keypoint_poses =
      KeypointPairPoses(*geometries, keypoint_matches, RefinementSettings(options.Matching()));
  if (!rematch) {
    GuidedSequencePairs(result->junctions, result->graphs, *geometries, keypoint_poses, options.Matching(), progress,
                        &result->pairs, diagnostics);
  } else {
    result->pairs = MatchSequencePairs(pairs, *geometries, result->junctions, result->graphs, options.Matching(),
                                       progress, diagnostics, keypoint_poses);
  }
  int& recentred = result->initialization.recentred_pairs;
  for (const MatchingDiagnostics& pair : *diagnostics) recentred += pair.recentred;
  LOG(INFO) << "matching: " << recentred << " of " << pairs.size()
            << " pairs matched with the gates centred on a pose hypothesis (keypoints, neighbouring pairs)";
  if (recentred > 0) {
    // Their verified poses changed: the odometry's noise is measured again from the final ones.
    bool wider_than_declared = false;
    MeasureOdometryNoise(sequence, options, pairs, *diagnostics, &wider_than_declared, result);
  }
  return Status::Ok();
}

// The initial trajectory: the images' relative poses and the odometry fused by their
// uncertainties (SolvePoseGraph), before triangulation.
Status InitialTrajectory(const Sequence& sequence, const PipelineOptions& options,
                         const std::vector<MatchingDiagnostics>& diagnostics, PipelineResult* result) {
  const Clock::time_point start = Clock::now();
  InitializationSummary& summary = result->initialization;
  result->evidence.pair_inliers.clear();
  for (const MatchingDiagnostics& pair : diagnostics) result->evidence.pair_inliers.push_back(pair.refinement.inliers);
  std::vector<RelativePoseConstraint> constraints = VisualConstraints(
      result->pairs, result->junctions, diagnostics, RefinementSettings(options.Matching()), &summary.pairs);
  for (RelativePoseConstraint& constraint : constraints) {
    for (const std::array<int, 3>& loop : summary.loops) {
      if (constraint.frame_i == loop[0] && constraint.frame_j == loop[1]) constraint.robust = false;
    }
  }
  // The pose graph solves for the odometry's rotation bias: its odometry factors are weighted by
  // the spread about the bias.
  OdometryNoise noise = summary.used;
  PoseGraphOptions pose_graph;
  if (summary.rotation.valid) {
    noise.rotation_sigma = summary.rotation.sigma;
    pose_graph.rotation_bias_start = summary.rotation.bias;
    // The images' own rotation noise (about 1e-4 rad) is the floor: an axis on which the odometry
    // looks exact is as certain as the images can tell.
    pose_graph.rotation_sigmas = summary.rotation.axis_sigmas.cwiseMax(kImageRotationSigmaFloor);
  }
  std::vector<Pose3> world_T_base;
  SFM_RETURN_IF_ERROR(SolvePoseGraph(OdometryBasePoses(sequence), sequence.calibration.base_T_camera, noise,
                                     options.bundle_adjustment_options, constraints, pose_graph, &world_T_base,
                                     &summary.pose_graph));
  result->world_T_camera_initial = CamerasFromBases(world_T_base, sequence.calibration.base_T_camera);
  summary.seconds = SecondsSince(start);
  const VisualConstraintCounts& counts = summary.pairs;
  LOG(INFO) << "initial trajectory: " << counts.constraints << " of " << counts.pairs
            << " pairs gave a relative pose (no pose: " << counts.too_few_matches << " too few matches, "
            << counts.too_few_inliers << " too few inliers, " << counts.inconsistent_with_prior
            << " beyond the odometry's gate, " << counts.no_information << " without information); pose graph "
            << summary.pose_graph.iterations << " iterations, cost " << summary.pose_graph.initial_cost << " -> "
            << summary.pose_graph.final_cost << ", " << summary.pose_graph.constraints_rejected
            << " pairs beyond 3 sigma, odometry rotation bias " << summary.pose_graph.rotation_bias.transpose()
            << " rad per frame; " << summary.seconds << " s";
  return Status::Ok();
}

// Loop closure (docs/initialization.md, "Loop closure"): pairs far apart along the trajectory whose
// views overlap on the initial trajectory (LoopCandidates) are matched like any pair, under the
// initial trajectory with the odometry's noise over every frame between them; a pair whose matches
// give a relative pose (the matcher's refinement inside that uncertainty, then
// RelativePoseFromMatches) joins the matched pairs: its matches join the tracks, its pose the pose
// graph. Returns whether any did.
bool CloseLoops(const Sequence& sequence, const PipelineOptions& options, Progress* progress,
                std::vector<MatchingDiagnostics>* diagnostics, PipelineResult* result) {
  const Calibration& calibration = sequence.calibration;
  const Eigen::Matrix3d K = calibration.camera.K();
  const std::vector<std::pair<int, int>> candidates =
      LoopCandidates(K, calibration.camera.width, calibration.camera.height, result->world_T_camera_initial,
                     result->landmarks);
  InitializationSummary& summary = result->initialization;
  summary.loop_candidates = static_cast<int>(candidates.size());
  if (candidates.empty()) return false;
  const std::vector<Pose3> bases = BasesFromCameras(result->world_T_camera_initial, calibration.base_T_camera);
  const MatchingOptions matching = options.Matching();
  std::vector<std::pair<int, int>> pairs;
  std::vector<PairGeometry> geometries;
  for (const auto& [a, b] : candidates) {
    const PairGeometry geometry = PairGeometryOnTrajectory(calibration, bases, a, b, summary.used);
    if (!(geometry.camera2_T_camera1.translation.allFinite() && geometry.covariance.allFinite())) continue;
    pairs.emplace_back(a, b);
    geometries.push_back(geometry);
  }
  std::vector<MatchingDiagnostics> pair_diagnostics;
  std::vector<FramePairMatches> matches = MatchSequencePairs(pairs, geometries, result->junctions, result->graphs,
                                                             matching, progress, &pair_diagnostics);
  for (size_t p = 0; p < pairs.size(); ++p) {
    // A wrong loop bends the whole trajectory: twice the inliers a pair's pose needs.
    if (pair_diagnostics[p].refinement.inliers < kLoopInlierFactor * matching.refine_min_inliers) continue;
    VisualConstraintCounts counts;
    if (VisualConstraints({matches[p]}, result->junctions, {pair_diagnostics[p]}, RefinementSettings(matching),
                          &counts)
            .empty()) {
      continue;
    }
    summary.loops.push_back({pairs[p].first, pairs[p].second, pair_diagnostics[p].refinement.inliers});
    result->pairs.push_back(std::move(matches[p]));
    diagnostics->push_back(std::move(pair_diagnostics[p]));
  }
  LOG(INFO) << "loop closure: " << summary.loops.size() << " of " << candidates.size()
            << " candidate pairs gave a relative pose";
  return !summary.loops.empty();
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

// Tracks, then 3D points and lines on the trajectory world_T_camera (the initial one, or after
// RematchAfterAdjustment the refined one).
void Reconstruct(const Sequence& sequence, const PipelineOptions& options, const std::vector<Pose3>& world_T_camera,
                 PipelineResult* result) {
  TrackBuildReport track_report;
  result->tracks = BuildTracks(result->junctions, result->pairs, &track_report);
  LOG(INFO) << "tracks: " << result->tracks.size() << " from " << track_report.matches << " matches ("
            << track_report.rejected_junction_conflict + track_report.rejected_segment_conflict
            << " rejected as inconsistent, " << track_report.skipped_partial_occlusion
            << " partial matches at a T or X not joined)";
  TriangulationReport triangulation_report;
  result->landmarks = TriangulateTracks(sequence.calibration.camera.K(), world_T_camera,
                                        result->junctions, result->tracks, options.triangulation,
                                        &triangulation_report);
  result->unobservable_lines = triangulation_report.Count(LineStatus::kUnobservable);
  LOG(INFO) << "triangulated " << result->landmarks.points.size() << " points and "
            << result->landmarks.lines.size() << " lines (" << result->unobservable_lines
            << " lines unobservable: parallel to the motion)";
}

// With --v=1: every landmark the floor prior held, with its junction types, for the diagnosis of
// the odometry scale it gives (docs/bundle_adjustment.md, "Floor prior").
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
void RecordTrackExtension(const TrackExtensionReport& report, size_t tracks, Clock::time_point start,
                          PipelineResult* result) {
  TrackExtensionSummary& summary = result->track_extension;
  summary.ran = true;
  summary.observations_added = report.observations_added;
  summary.tracks_merged = report.tracks_merged;
  summary.ambiguous = report.ambiguous;
  summary.points_changed = static_cast<int>(report.changed_points.size());
  summary.lines_changed = static_cast<int>(report.changed_lines.size());
  summary.seconds = SecondsSince(start);
  LOG(INFO) << "track extension: " << summary.points_triangulated_again
            << " points triangulated again on the solved poses, " << report.observations_added
            << " observations added, "
            << report.tracks_merged << " tracks merged (" << report.merges_refused << " refused), "
            << report.ambiguous << " ambiguous projections, " << report.gate_too_wide << " gates too wide, "
            << report.no_junction << " empty, " << report.incompatible
            << " with no compatible junction; refused merges: " << report.merge_overlap
            << " sharing a frame, " << report.merge_disagree << " disagreeing points, "
            << report.merge_unexplained << " not explained by the point; " << summary.points_changed
            << " points and " << summary.lines_changed << " lines changed; now " << tracks << " tracks; "
            << summary.seconds << " s";
}

// The bundle adjustment's steps with the track extension between its first fine solve and its
// outlier rounds, which then judge the new observations as the old ones and whose solves refine
// the changed map with the poses (docs/tracks_and_triangulation.md, "Track extension"; COLMAP's
// IterativeGlobalRefinement: adjust, complete and merge tracks, filter). The solves start from
// reconstruction->world_T_base at the odometry's scale factor 1; the odometry is the prior.
Status AdjustAndExtendTracks(const std::vector<Pose3>& world_T_base_odometry, const PipelineOptions& options,
                             Progress* progress, Reconstruction* reconstruction,
                             BundleAdjustmentSummary* summary, PipelineResult* result) {
  BundleAdjustment adjustment(world_T_base_odometry, /*odometry_scale_start=*/1,
                              options.bundle_adjustment_options, reconstruction, summary);
  adjustment.SetIterationHook([progress](int solve, int iteration) {
    progress->Show("bundle adjustment",
                   "solve " + std::to_string(solve) + ", iteration " + std::to_string(iteration));
  });
  SFM_RETURN_IF_ERROR(adjustment.Start());
  SFM_RETURN_IF_ERROR(adjustment.SolveCoarse());
  SFM_RETURN_IF_ERROR(adjustment.SolveFine());
  if (options.extend_tracks && !adjustment.finished()) {
    const Clock::time_point start = Clock::now();
    TrackExtensionReport report;
    Eigen::Vector2d box_min, box_max;
    DetectionBox(reconstruction->calibration.camera, options, &box_min, &box_max);
    // Tracks whose point failed on the start's poses (a long track's reprojection error pushed
    // past the bound by the drift) are triangulated again on the solved ones, then extended.
    result->track_extension.points_triangulated_again = TriangulateMissingPoints(
        reconstruction->calibration.camera.K(), reconstruction->WorldTCamera(), reconstruction->junctions,
        reconstruction->tracks, options.triangulation.point, &reconstruction->landmarks);
    ExtendTracks(options.track_extension, box_min, box_max, reconstruction, &report);
    RecordTrackExtension(report, reconstruction->tracks.size(), start, result);
    SFM_RETURN_IF_ERROR(adjustment.AcceptChangedMap());
  }
  SFM_RETURN_IF_ERROR(adjustment.Filter());
  adjustment.Finish();
  return Status::Ok();
}

// Bundle adjustment from the trajectory world_T_camera (the landmarks' own), the odometry its
// prior, the tracks extended in it: refined poses, landmarks and tracks.
Status Refine(const Sequence& sequence, const PipelineOptions& options, const std::vector<Pose3>& world_T_camera,
              Progress* progress, PipelineResult* result) {
  const std::vector<Pose3> world_T_base_odometry = OdometryBasePoses(sequence);
  Reconstruction reconstruction;
  reconstruction.calibration = sequence.calibration;
  reconstruction.calibration.odometry_noise = result->initialization.used;
  reconstruction.world_T_base = BasesFromCameras(world_T_camera, sequence.calibration.base_T_camera);
  reconstruction.junctions = std::move(result->junctions);
  reconstruction.tracks = std::move(result->tracks);
  reconstruction.landmarks = std::move(result->landmarks);
  BundleAdjustmentSummary summary;
  const Status status =
      AdjustAndExtendTracks(world_T_base_odometry, options, progress, &reconstruction, &summary, result);
  progress->Finish();
  result->junctions = std::move(reconstruction.junctions);
  result->tracks = std::move(reconstruction.tracks);
  result->landmarks = std::move(reconstruction.landmarks);
  SFM_RETURN_IF_ERROR(status);
  result->unobservable_lines += summary.lines_unobservable;
  result->bundle_adjustment = summary;
  result->world_T_camera_refined =
      CamerasFromBases(reconstruction.world_T_base, sequence.calibration.base_T_camera);
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

// The pairs whose matches the refined trajectory contradicts (a repeated pattern matched a period
// off in the odometry's gates) matched again in the odometry's band centred on the refined poses;
// when any was, the tracks and landmarks are built again on the refined trajectory and adjusted
// again, the odometry still the prior (docs/matching.md, "Matching again after the adjustment").
Status RematchAfterAdjustment(const Sequence& sequence, const PipelineOptions& options, Progress* progress,
                              PipelineResult* result) {
  const std::vector<Pose3> bases =
      BasesFromCameras(result->world_T_camera_refined, sequence.calibration.base_T_camera);
  std::vector<PairGeometry> geometries;
  for (const FramePairMatches& pair : result->pairs) {
    geometries.push_back(
        PairGeometryOnTrajectory(sequence.calibration, bases, pair.frame_a, pair.frame_b, result->initialization.used));
  }
  int& rematched = result->initialization.pairs_rematched_after_adjustment;
  std::vector<int>* inliers = &result->evidence.pair_inliers;
  if (inliers->size() != result->pairs.size()) inliers = nullptr;
  rematched =
      RematchDisagreeingPairs(geometries, result->junctions, result->graphs, options.Matching(), &result->pairs, inliers);
  LOG(INFO) << "matching again after the adjustment: " << rematched << " of " << result->pairs.size()
            << " pairs whose matches the refined trajectory contradicts";
  if (rematched == 0) return Status::Ok();
  const std::vector<Pose3> start = result->world_T_camera_refined;
  Reconstruct(sequence, options, start, result);
  return Refine(sequence, options, start, progress, result);
}

// The odometry's distance noise and scale error measured against the refined trajectory's step
// lengths (docs/initialization.md, "Odometry noise from the data"): reported, with a warning when
// the declared translation sigma contradicts it.
void MeasureOdometryTranslationNoise(const Sequence& sequence, const PipelineOptions& options,
                                     PipelineResult* result) {
  InitializationSummary& summary = result->initialization;
  summary.translation = EstimateOdometryTranslationNoise(
      OdometryBasePoses(sequence),
      BasesFromCameras(result->world_T_camera_refined, sequence.calibration.base_T_camera),
      options.bundle_adjustment_options.odometry_min_distance_m);
  if (!summary.translation.valid) return;
  const double measured = summary.translation.EffectiveSigma();
  LOG(INFO) << "odometry translation noise from " << summary.translation.steps << " refined steps: scale error "
            << summary.translation.scale_error << ", distance noise " << summary.translation.distance_sigma
            << " of the distance; declared " << summary.declared.translation_sigma;
  if (sequence.calibration.odometry_noise_given &&
      DeclaredSigmaContradicted(summary.declared.translation_sigma, measured)) {
    LOG(WARNING) << options.sequence_dir << "/sequence.yaml: odometry_translation_sigma "
                 << summary.declared.translation_sigma << " of the distance, but the refined trajectory measures "
                 << measured;
  }
}

// The refined trajectory against the odometry by the images alone (trajectory_evidence.h): the
// matches' epipolar fit under each trajectory, and the frames where the refined one leaves the
// odometry beyond its noise. A refined trajectory the matches fit worse than the odometry is
// returned with a warning, never silently.
void WeighTheEvidence(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  TrajectoryEvidence& evidence = result->evidence;
  const Eigen::Matrix3d K = sequence.calibration.camera.K();
  evidence.computed = true;
  evidence.epipolar_px_odometry =
      EpipolarEvidencePx(K, result->world_T_camera_odometry, result->junctions, result->pairs);
  evidence.epipolar_px_initial = EpipolarEvidencePx(K, result->world_T_camera_initial, result->junctions, result->pairs);
  evidence.epipolar_px_refined = EpipolarEvidencePx(K, result->world_T_camera_refined, result->junctions, result->pairs);
  evidence.frames_disagreeing_with_odometry = FramesDisagreeingWithOdometry(
      OdometryBasePoses(sequence), BasesFromCameras(result->world_T_camera_refined, sequence.calibration.base_T_camera),
      result->initialization.used, options.bundle_adjustment_options.odometry_min_distance_m);
  evidence.refined_worse_than_odometry = evidence.epipolar_px_refined > evidence.epipolar_px_odometry;
  LOG(INFO) << "the matches' epipolar fit (median px): odometry " << evidence.epipolar_px_odometry << ", initial "
            << evidence.epipolar_px_initial << ", refined " << evidence.epipolar_px_refined << "; "
            << evidence.frames_disagreeing_with_odometry.size()
            << " refined steps beyond 3 sigma of the odometry's noise";
  const BundleAdjustmentSummary& adjustment = result->bundle_adjustment;
  evidence.point_rms_px = adjustment.point_rms_px;
  evidence.line_rms_px = adjustment.line_rms_px;
  evidence.adjustment_converged = adjustment.converged;
  std::vector<double> moved;
  for (size_t f = 0; f < result->world_T_camera_refined.size(); ++f) {
    const Eigen::Vector3d refined = result->world_T_camera_refined[f].translation;
    moved.push_back((refined - result->world_T_camera_odometry[f].translation).norm());
    evidence.moved_by_adjustment_max_m = std::max(evidence.moved_by_adjustment_max_m,
                                                  (refined - result->world_T_camera_initial[f].translation).norm());
  }
  if (!moved.empty()) {
    evidence.moved_from_odometry_max_m = *std::max_element(moved.begin(), moved.end());
    std::nth_element(moved.begin(), moved.begin() + moved.size() / 2, moved.end());
    evidence.moved_from_odometry_median_m = moved[moved.size() / 2];
  }
  std::ostringstream text;
  if (evidence.refined_worse_than_odometry) {
    text << "the matches fit the odometry better than the refined trajectory (" << evidence.epipolar_px_odometry
         << " px against " << evidence.epipolar_px_refined << " px): the refined trajectory may be worse than the odometry";
    evidence.warnings.push_back(text.str());
  }
  if (adjustment.solves > 0 && !adjustment.converged) {
    evidence.warnings.push_back("the bundle adjustment stopped at its iteration limit, not at a minimum");
  }
  const double rms_limit = kUnreliableRmsLocationSigmas * options.Matching().location_sigma_px;
  if (adjustment.point_rms_px > rms_limit) {
    text.str("");
    text << "the points' reprojection RMS is " << adjustment.point_rms_px << " px (above " << rms_limit
         << "): wrong matches or a wrong calibration";
    evidence.warnings.push_back(text.str());
  }
  const VisualConstraintCounts& pairs = result->initialization.pairs;
  if (2 * pairs.constraints < pairs.pairs) {
    text.str("");
    text << "only " << pairs.constraints << " of " << pairs.pairs
         << " image pairs gave a relative pose: the odometry alone carries the rest";
    evidence.warnings.push_back(text.str());
  }
  for (const std::string& warning : evidence.warnings) LOG(WARNING) << warning;
}

void AddEdgesBetweenPoints(const PipelineOptions& options, const std::vector<Pose3>& poses,
                           const WireframeSelectionReport& report, PipelineResult* result);

// The landmarks the wireframe draws (docs/tracks_and_triangulation.md, "Wireframe vertices"):
// judged on the final poses; bundle adjustment and the COLMAP model keep every landmark.
void SelectWireframe(const Sequence& sequence, const PipelineOptions& options, PipelineResult* result) {
  const std::vector<Pose3>& poses =
      result->world_T_camera_refined.empty() ? result->world_T_camera_initial : result->world_T_camera_refined;
  const WireframeOptions& wireframe = options.triangulation.wireframe;
  const Eigen::Matrix3d K = sequence.calibration.camera.K();
  const PoseDrift drift = WireframePoseDrift(wireframe, poses);
  WireframeSelectionReport& report = result->wireframe_selection;
  result->wireframe_landmarks =
      SelectWireframeLandmarks(K, poses, result->landmarks, result->junctions, wireframe, drift, &report);
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
  ManhattanLineOptions manhattan;
  manhattan.pixel_sigma_px = report.pixel_sigma_px > 0 ? report.pixel_sigma_px : wireframe.pixel_sigma_px;
  manhattan.drift = drift;
  manhattan.level = wireframe.consistency_level;
  manhattan.min_plane_angle_deg = options.triangulation.line.min_plane_angle_deg;
  manhattan.wireframe = wireframe;
  manhattan.line = options.triangulation.line;
  const Camera& camera = sequence.calibration.camera;
  const double border_margin = options.segments.border_margin;
  manhattan.seen_by_image = [&camera, border_margin](const Eigen::Vector2d& pixel) {
    return SeenByStoredImage(camera, pixel, border_margin);
  };
  ManhattanLineReport& placed = result->manhattan_lines;
  PlaceManhattanLines(K, poses, result->junctions, result->tracks, manhattan, &result->wireframe_landmarks,
                      &placed);
  LOG(INFO) << "wireframe: " << placed.placed << " lines along the motion placed by the dominant directions"
            << " (support " << placed.directions.support << ", " << placed.candidates << " candidates, "
            << placed.inconsistent << " off every direction, " << placed.ambiguous << " ambiguous, "
            << placed.unbounded << " unbounded, " << placed.ends_disagree << " far ends apart, "
            << placed.undetermined << " undetermined; " << placed.leaving_view
            << " of the placed leave the view)";
  if (options.topology_edges) AddEdgesBetweenPoints(options, poses, report, result);
  LinePointAgreementOptions agreement;
  agreement.pixel_sigma_px = report.pixel_sigma_px > 0 ? report.pixel_sigma_px : wireframe.pixel_sigma_px;
  agreement.drift = drift;
  agreement.level = wireframe.consistency_level;
  LinePointAgreementReport& agreed = result->line_point_agreement;
  AgreeLinesAndPoints(K, poses, result->junctions, agreement, &result->wireframe_landmarks, &agreed);
  // The fused positions are the map's too, so that the COLMAP model's points and wireframe.ply's
  // vertices of one track stay one position.
  std::unordered_map<int, Eigen::Vector3d> fused;
  for (const PointLandmark& point : result->wireframe_landmarks.points) {
    if (point.track_id >= 0) fused[point.track_id] = point.position;
  }
  for (PointLandmark& point : result->landmarks.points) {
    const auto it = fused.find(point.track_id);
    if (it != fused.end()) point.position = it->second;
  }
  LOG(INFO) << "wireframe: lines and points agree: " << agreed.ends_at_points << " more far ends at points, "
            << agreed.points_on_lines << " points fused with a line they lie on, " << agreed.splits
            << " line edges split at them (" << agreed.candidates << " candidates)";
}

// AddTopologyEdges with the pipeline's settings.
void AddEdgesBetweenPoints(const PipelineOptions& options, const std::vector<Pose3>& poses,
                           const WireframeSelectionReport& report, PipelineResult* result) {
  const WireframeOptions& wireframe = options.triangulation.wireframe;
  TopologyEdgeOptions topology = options.topology_edge_options;
  topology.pixel_sigma_px = report.pixel_sigma_px > 0 ? report.pixel_sigma_px : wireframe.pixel_sigma_px;
  topology.max_gap_px = -std::log(options.junctions.min_probability) / options.junctions.endpoint_model.mu;
  topology.min_plane_angle_deg = options.triangulation.line.min_plane_angle_deg;
  AddTopologyEdges(poses, result->junctions, topology, &result->wireframe_landmarks, &result->topology_edges);
  const TopologyEdgeReport& edges = result->topology_edges;
  LOG(INFO) << "wireframe: " << edges.edges << " edges between drawn points joined in the images ("
            << edges.candidates << " candidates, " << edges.unsupported
            << " not shown by enough of the frames seeing both, " << edges.undetermined
            << " in an epipolar plane across the motion, " << edges.splits << " splits at points on them); "
            << edges.lines_dropped << " lines lying on them dropped";
}

}  // namespace

MatchingOptions PipelineOptions::Matching() const {
  MatchingOptions options = matching;
  options.endpoint_model = junctions.endpoint_model;
  return options;
}

Status PipelineOptions::Check() const {
  if (output_dir.empty()) return Status::Error("--output must name a directory");
  if (threads < 0) return Status::Error("threads must be >= 0");
  SFM_RETURN_IF_ERROR(segments.Check());
  SFM_RETURN_IF_ERROR(junctions.Check());
  SFM_RETURN_IF_ERROR(Matching().Check());
  SFM_RETURN_IF_ERROR(triangulation.Check());
  if (extend_tracks) SFM_RETURN_IF_ERROR(track_extension.Check());
  if (topology_edges) SFM_RETURN_IF_ERROR(topology_edge_options.Check());
  return bundle_adjustment_options.Check();
}

Status RunPipeline(const PipelineOptions& options, PipelineResult* result_out) {
  const Clock::time_point start = Clock::now();
  SFM_RETURN_IF_ERROR(options.Check());
  const ThreadLimit thread_limit(options.threads);

  // 1. Read and validate all input before anything is written.
  Sequence sequence;
  SFM_RETURN_IF_ERROR(ReadSequence(options.sequence_dir, &sequence));
  SFM_RETURN_IF_ERROR(CheckOutputNames(sequence));
  LOG(INFO) << "sequence " << options.sequence_dir << ": " << sequence.frames.size() << " frames, "
            << sequence.calibration.camera.width << "x" << sequence.calibration.camera.height
            << (sequence.has_groundtruth ? ", with ground truth" : ", no ground truth");
  Progress progress(options.show_progress);
  StageTimer stages(&progress);
  std::vector<std::pair<int, int>> pairs;
  std::vector<PairGeometry> pair_geometries;
  SFM_RETURN_IF_ERROR(OdometryPairGeometries(sequence, options.sequence_dir, sequence.calibration.odometry_noise,
                                             &pairs, &pair_geometries));
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(options.output_dir));

  PipelineResult result;
  result.world_T_camera_odometry = CameraPoses(sequence, /*groundtruth=*/false);
  if (sequence.has_groundtruth) result.world_T_camera_truth = CameraPoses(sequence, /*groundtruth=*/true);

  // 2. Front end, matching, back end.
  Clock::time_point stage_start = Clock::now();
  stages.Start("junction detection");
  std::vector<KeypointCorrespondences> keypoint_matches;
  {
    std::vector<FrameKeypoints> keypoints;
    SFM_RETURN_IF_ERROR(DetectJunctionsOfAllFrames(sequence, options, &progress, &keypoints, &result));
    keypoint_matches = MatchConsecutiveKeypoints(pairs, keypoints);
  }
  result.times.frontend = SecondsSince(stage_start);
  stage_start = Clock::now();
  stages.Start("matching");
  std::vector<MatchingDiagnostics> diagnostics;
  SFM_RETURN_IF_ERROR(
      MatchFramePairs(sequence, options, pairs, keypoint_matches, &pair_geometries, &progress, &diagnostics, &result));
  result.times.matching = SecondsSince(stage_start);
  stage_start = Clock::now();
  stages.Start("initial trajectory");
  SFM_RETURN_IF_ERROR(InitialTrajectory(sequence, options, diagnostics, &result));
  stages.Start("tracks and triangulation");
  Reconstruct(sequence, options, result.world_T_camera_initial, &result);
  stages.Start("loop closure");
  if (CloseLoops(sequence, options, &progress, &diagnostics, &result)) {
    SFM_RETURN_IF_ERROR(InitialTrajectory(sequence, options, diagnostics, &result));
    Reconstruct(sequence, options, result.world_T_camera_initial, &result);
  }
  if (options.bundle_adjustment) {
    stages.Start("bundle adjustment");
    SFM_RETURN_IF_ERROR(Refine(sequence, options, result.world_T_camera_initial, &progress, &result));
    SFM_RETURN_IF_ERROR(RematchAfterAdjustment(sequence, options, &progress, &result));
    stages.Start("evidence");
    MeasureOdometryTranslationNoise(sequence, options, &result);
    WeighTheEvidence(sequence, options, &result);
  }
  stages.Start("wireframe selection");
  SelectWireframe(sequence, options, &result);
  result.times.backend = SecondsSince(stage_start);
  if (result.world_T_camera_truth) {
    result.drift_odometry = ComputeDrift(result.world_T_camera_odometry, *result.world_T_camera_truth);
    result.drift_initial = ComputeDrift(result.world_T_camera_initial, *result.world_T_camera_truth);
    if (!result.world_T_camera_refined.empty()) {
      result.drift_refined = ComputeDrift(result.world_T_camera_refined, *result.world_T_camera_truth);
    }
  }

  // 3. Outputs. The report shows the time up to here; metrics.json's total also counts the
  // report's writing (the largest output; the small files after it take milliseconds).
  LOG(INFO) << "writing the outputs in " << options.output_dir;
  result.times.total = SecondsSince(start);
  stages.Start("report");
  // The report reads the frames it draws from disk again: no image is kept through the run.
  SFM_RETURN_IF_ERROR(WriteReport(sequence, result, /*undistorted_images_or_empty=*/{}, options.output_dir));
  result.times.total = SecondsSince(start);
  stages.Start("outputs");
  SFM_RETURN_IF_ERROR(WriteOutputs(sequence, result, options.output_dir));
  stages.End();
  progress.Finish();
  // The log's last line.
  LOG(INFO) << "time: " << stages.Text() << "; total " << SecondsSince(start) << " s (metrics.json: frontend "
            << result.times.frontend << " s, matching " << result.times.matching << " s, backend "
            << result.times.backend << " s)";
  if (result_out) *result_out = std::move(result);
  return Status::Ok();
}

}  // namespace sfm

// What one junction_sfm run computes, stage by stage; the outputs are written from it.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/initialization/odometry_noise_estimate.h"
#include "backend/initialization/pose_graph.h"
#include "backend/initialization/visual_constraints.h"
#include "backend/metrics/drift.h"
#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/line_point_agreement.h"
#include "backend/triangulation/manhattan_lines.h"
#include "backend/triangulation/topology_edges.h"
#include "backend/triangulation/wireframe_selection.h"
#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"
#include "geometry/pose.h"

namespace sfm {

struct StageTimes {
  double frontend = 0, matching = 0, backend = 0, total = 0;  // seconds
};

// What the track extension inside the bundle adjustment did (PipelineOptions::extend_tracks).
struct TrackExtensionSummary {
  bool ran = false;
  int points_triangulated_again = 0;  // tracks without a point, triangulated on the solved poses
  int observations_added = 0;    // unassigned junctions joined to a track
  int tracks_merged = 0;         // tracks absorbed into another
  int ambiguous = 0;             // projections with two or more compatible junctions in the gate
  int points_changed = 0, lines_changed = 0;
  double seconds = 0;            // the step's own time
};

// The initial trajectory (docs/initialization.md): the odometry's noise measured against the
// images, and the pose graph that fuses the images' relative poses with the odometry.
struct InitializationSummary {
  bool ran = false;
  VisualConstraintCounts pairs;            // of the matching whose geometry the run kept
  OdometryRotationEstimate rotation;       // from the images' relative rotations
  OdometryTranslationEstimate translation; // from the refined trajectory's step lengths
  OdometryNoise declared;                  // sequence.yaml's (or the default)
  OdometryNoise used;                      // what the matcher's gates and the priors were weighted by
  bool rematched = false;                  // matching ran again with the measured noise
  // Pairs whose matches came from gates centred on a pose hypothesis instead of the odometry
  // (GuidedPassOrHypotheses): by the keypoints' pose, and by the neighbouring pairs' poses.
  int recentred_pairs = 0;
  // Pairs matched again under the refined trajectory, which their matches contradicted
  // (RematchAfterAdjustment); the map was then built and adjusted again.
  int pairs_rematched_after_adjustment = 0;
  // Loop closure: pairs whose views overlap far apart along the trajectory, matched; those that
  // gave a relative pose, (frame a, frame b, inliers).
  int loop_candidates = 0;
  std::vector<std::array<int, 3>> loops;
  PoseGraphSummary pose_graph;
  double seconds = 0;
};

// The run's own evidence on its trajectories, without ground truth (trajectory_evidence.h).
struct TrajectoryEvidence {
  bool computed = false;
  // Median over the matched pairs of the median |Sampson distance| of their matches, pixels.
  double epipolar_px_odometry = 0, epipolar_px_initial = 0, epipolar_px_refined = 0;
  // Frames whose refined step departs from the odometry's by more than 3 sigma of the noise used.
  std::vector<int> frames_disagreeing_with_odometry;
  // The matches fit the odometry better than the refined trajectory (the run warns).
  bool refined_worse_than_odometry = false;
  // The adjustment's RMS reprojection errors (points, lines), pixels, and whether every solve
  // ended by a convergence test.
  double point_rms_px = 0, line_rms_px = 0;
  bool adjustment_converged = false;
  // Inliers of each matched pair's pose (the matcher's refinement, or its refinement when matched
  // again after the adjustment; 0 without one), in the order of PipelineResult::pairs.
  std::vector<int> pair_inliers;
  // How far the camera centres moved: from the odometry to the refined trajectory (median and
  // largest over the frames), and in the adjustment (largest), metres.
  double moved_from_odometry_median_m = 0, moved_from_odometry_max_m = 0, moved_by_adjustment_max_m = 0;
  // What says the run may be unreliable, one sentence each (also logged as warnings).
  std::vector<std::string> warnings;
};

struct PipelineResult {
  std::vector<Junctions> junctions;       // per frame
  std::vector<TopologyGraph> graphs;      // per frame
  std::vector<FramePairMatches> pairs;    // every pair matched (consecutive and two back)
  std::vector<JunctionTrack> tracks;
  Landmarks landmarks;
  // The landmarks wireframe.ply draws: those SelectWireframeLandmarks keeps on the final poses.
  Landmarks wireframe_landmarks;
  WireframeSelectionReport wireframe_selection;
  TopologyEdgeReport topology_edges;      // the edges between drawn points (AddTopologyEdges)
  LinePointAgreementReport line_point_agreement;  // lines and points made to agree (AgreeLinesAndPoints)
  ManhattanLineReport manhattan_lines;  // lines along the motion placed (PlaceManhattanLines)
  int unobservable_lines = 0;             // segment tracks dropped as parallel to the motion
  std::vector<Pose3> world_T_camera_odometry;
  std::vector<Pose3> world_T_camera_initial;               // the pose graph's (InitializationSummary)
  std::vector<Pose3> world_T_camera_refined;               // empty until bundle adjustment ran
  InitializationSummary initialization;
  TrajectoryEvidence evidence;
  BundleAdjustmentSummary bundle_adjustment;               // when it ran (floor prior, counts)
  TrackExtensionSummary track_extension;
  std::optional<std::vector<Pose3>> world_T_camera_truth;  // when the sequence has ground truth
  std::optional<DriftMetrics> drift_odometry, drift_refined;  // against the ground truth
  std::optional<DriftMetrics> drift_initial;                  // the initial trajectory's
  StageTimes times;
};

}  // namespace sfm

// What one junction_sfm run computes, stage by stage; the outputs are written from it.
#pragma once

#include <optional>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/metrics/drift.h"
#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/wireframe_selection.h"
#include "geometry/pose.h"
#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"

namespace sfm {

struct StageTimes {
  double frontend = 0, matching = 0, backend = 0, total = 0;  // seconds
};

// What the re-triangulation on the refined poses did (PipelineOptions::retriangulate_refined).
struct RetriangulationSummary {
  bool ran = false;
  bool second_adjustment = false;  // "full": the poses are the second adjustment's
  int points_added = 0, lines_added = 0;
  int observations_removed = 0;  // outlier observations of the new landmarks, on the refined poses
};

// What the track extension on the refined poses did (PipelineOptions::extend_tracks).
struct TrackExtensionSummary {
  bool ran = false;
  int observations_added = 0;    // unassigned junctions joined to a track
  int tracks_merged = 0;         // tracks absorbed into another
  int ambiguous = 0;             // projections with two or more compatible junctions in the gate
  int observations_removed = 0;  // outlier observations of the changed landmarks, on the refined poses
  int points_changed = 0, lines_changed = 0;
  bool second_adjustment = false;  // the poses are a second adjustment's (extend_tracks_resolve)
  double seconds = 0;            // the step's own time (extension and refinement)
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
  int unobservable_lines = 0;             // segment tracks dropped as parallel to the motion
  std::vector<Pose3> world_T_camera_odometry;
  std::vector<Pose3> world_T_camera_refined;               // empty until bundle adjustment ran
  BundleAdjustmentSummary bundle_adjustment;               // when it ran (floor prior, counts)
  RetriangulationSummary retriangulation;
  TrackExtensionSummary track_extension;
  std::optional<std::vector<Pose3>> world_T_camera_truth;  // when the sequence has ground truth
  std::optional<DriftMetrics> drift_odometry, drift_refined;  // against the ground truth
  StageTimes times;
};

}  // namespace sfm

// The junction_sfm pipeline as a library function, so tests can run it without a process:
// read and validate the sequence, run each stage, write the SPEC section 3 outputs.
#pragma once

#include <string>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/triangulation/landmark_merge.h"
#include "backend/triangulation/track_extension.h"
#include "backend/triangulation/triangulation_options.h"
#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/matching/matching_options.h"
#include "frontend/segments/segment_detector.h"
#include "util/status.h"
#include "pipeline/pipeline_result.h"

namespace sfm {

// After the bundle adjustment, triangulate every track again on the refined poses
// (docs/tracks_and_triangulation.md, "Re-triangulation on the refined poses"): off; structure (the
// landmarks refined on the refined poses, which stay as they are); full (then a second bundle
// adjustment of everything, starting from the refined poses, the odometry still its prior).
enum class RetriangulateRefined { kOff, kStructure, kFull };

// Where the track extension runs (docs/tracks_and_triangulation.md, "Track extension"):
// inside the bundle adjustment, after its fine solve and outlier rounds, then two fine solves more
// and an outlier round (MapHook::kAfterFine); inside it on the coarse stage's poses, before its fine
// solves (kAfterCoarse); after it, the changed landmarks refined on the refined poses held fixed (the
// trajectory unchanged); or after it with a second bundle adjustment of everything starting from
// the refined poses (the odometry still the prior).
enum class TrackExtensionStage { kInAdjustment, kAfterCoarse, kAfterStructure, kAfterResolve };

struct PipelineOptions {
  std::string sequence_dir;   // a SPEC section 1 sequence directory
  std::string output_dir;     // created if needed; existing files of the same names are replaced
  bool show_progress = true;  // a progress line on stderr (only when stderr is a terminal)
  // Resampling of each frame to the undistorted image (lens distortion only; see
  // kDetectionInterpolation).
  UndistortInterpolation undistort_interpolation = kDetectionInterpolation;
  // Detect on a canvas holding the stored image's whole field of view (UndistortView::kFullView)
  // instead of the undistorted image of the stored size; junctions may then lie outside
  // [0, width) x [0, height) of K's pixel frame. Lens distortion only (docs/junction_results.md,
  // "Session 8: full field of view"; the default is kDetectionView's).
  bool undistort_full_view = kDetectionView == UndistortView::kFullView;
  SegmentDetectorOptions segments;
  JunctionDetectorOptions junctions;
  MatchingOptions matching;
  TriangulationOptions triangulation;
  bool bundle_adjustment = true;  // false: the outputs use the odometry poses and the first triangulation
  BundleAdjustmentOptions bundle_adjustment_options;
  RetriangulateRefined retriangulate_refined = RetriangulateRefined::kOff;
  // Which re-triangulated landmarks join the map (landmark_merge.h).
  RetriangulatedLandmarks retriangulated_landmarks = RetriangulatedLandmarks::kAddNew;
  // Extend and merge the tracks by projecting each point landmark into the frames its track misses
  // (track_extension.h), at the stage extend_tracks_stage says (by default inside the bundle
  // adjustment, TrackExtensionStage above; docs/tracks_and_triangulation.md, "Track extension").
  bool extend_tracks = true;
  TrackExtensionStage extend_tracks_stage = TrackExtensionStage::kInAdjustment;
  TrackExtensionOptions track_extension;

  // OK, or a message naming the first bad setting.
  Status Check() const;
};

// Runs everything. All input is read and validated, and every stage has run, before any output
// file is written; each output file is written atomically. So a failure never leaves a
// half-written file. `result` (optional) receives what was computed.
Status RunPipeline(const PipelineOptions& options, PipelineResult* result = nullptr);

}  // namespace sfm

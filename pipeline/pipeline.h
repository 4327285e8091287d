// The junction_sfm pipeline as a library function, so tests can run it without a process:
// read and validate the sequence, run each stage, write the SPEC section 3 outputs.
#pragma once

#include <string>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/triangulation/topology_edges.h"
#include "backend/triangulation/track_extension.h"
#include "backend/triangulation/triangulation_options.h"
#include "frontend/junctions/junction_options.h"
#include "frontend/matching/matching_options.h"
#include "frontend/segments/segment_detector.h"
#include "geometry/image_undistorter.h"
#include "pipeline/pipeline_result.h"
#include "util/status.h"

namespace sfm {

struct PipelineOptions {
  std::string sequence_dir;   // a SPEC section 1 sequence directory
  std::string output_dir;     // created if needed; existing files of the same names are replaced
  bool show_progress = true;  // a progress line on stderr (only when stderr is a terminal)
  // Resampling of each frame to the undistorted image (lens distortion only; see
  // kDetectionInterpolation).
  UndistortInterpolation undistort_interpolation = kDetectionInterpolation;
  // Detect on a canvas holding the stored image's whole field of view (UndistortView::kFullView)
  // instead of the undistorted image of the stored size; junctions may then lie outside
  // [0, width) x [0, height) of K's pixel frame. Lens distortion only (docs/decisions.md;
  // the default is kDetectionView's).
  bool undistort_full_view = kDetectionView == UndistortView::kFullView;
  SegmentDetectorOptions segments;
  JunctionDetectorOptions junctions;
  // Its endpoint_model is not read: Matching() hands down junctions.endpoint_model.
  MatchingOptions matching;
  TriangulationOptions triangulation;
  bool bundle_adjustment = true;  // false: the outputs use the odometry poses and the first triangulation
  BundleAdjustmentOptions bundle_adjustment_options;
  // Extend and merge the tracks by projecting each point landmark into the frames its track misses
  // (track_extension.h), inside the bundle adjustment after its first fine solve, whose outlier
  // rounds then judge the new observations (docs/tracks_and_triangulation.md, "Track extension").
  bool extend_tracks = true;
  TrackExtensionOptions track_extension;
  // Wireframe edges between drawn points that the images show joined by one line segment
  // (topology_edges.h). Of topology_edge_options, pixel_sigma_px, max_gap_px and
  // min_plane_angle_deg are not read: the run uses the wireframe selection's pixel noise, the
  // junction detector's end-point allowance, -ln(junctions.min_probability) /
  // junctions.endpoint_model.mu, and the line triangulation's min_plane_angle_deg.
  bool topology_edges = true;
  TopologyEdgeOptions topology_edge_options;

  // `matching` with the end-point model of junction detection: eq. (5) models the detected
  // end-points once, for both stages.
  MatchingOptions Matching() const;
  // OK, or a message naming the first bad setting.
  Status Check() const;
};

// Runs everything. All input is read and validated, and every stage has run, before any output
// file is written; each output file is written atomically. So a failure never leaves a
// half-written file. `result` (optional) receives what was computed.
Status RunPipeline(const PipelineOptions& options, PipelineResult* result = nullptr);

}  // namespace sfm

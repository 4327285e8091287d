// Guided track extension and merging on the refined poses: each 3D point landmark is projected
// into the frames its track does not see, and a junction there joins the track when it is the only
// one inside the landmark's uncertainty gate whose segments point where the track's lines project.
// A junction that already belongs to another track merges the two tracks (and their landmarks)
// when their frames do not overlap, the point explains every view of the other track (each is the
// one compatible junction in its frame's gate) and the two points agree within their uncertainty.
// docs/tracks_and_triangulation.md, "Track extension".
// Pixels are undistorted pixels (K only); positions in the world frame, metres.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/reconstruction.h"
#include "backend/triangulation/triangulation_options.h"
#include "geometry/pose.h"
#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"
#include "util/status.h"

namespace sfm {

struct TrackExtensionOptions {
  // Pixel noise of a junction location, pixels, > 0: the detector's location error.
  double pixel_sigma_px = kJunctionLocationErrorPx;
  // The refined poses' rotation error as a random walk per frame, radians, >= 0: the wireframe's
  // 0.0002 (what bundle adjustment leaves of the odometry's drift, docs/tracks_and_triangulation.md).
  // A frame d frames from the nearest view of the track adds (fx * step)^2 d to the gate's variance.
  double rotation_step_rad = 0.0002;
  // Probability mass of the gate, in (0, 1): a junction is inside when its Mahalanobis distance to
  // the projection, under the projected covariance, is within the chi-square 2-dof quantile.
  double gate_probability = 0.999;
  // Upper bound of the gate's radius, pixels, > 0: a landmark whose projection is this uncertain
  // (a far point in a frame along its viewing ray) cannot pick one junction among crowded ones.
  double max_gate_px = 4;
  // Largest angle between a junction segment and the direction the track predicts for it (its 3D
  // line projected, or the segment of the track's nearest view), degrees, in (0, 90).
  double max_angle_deg = 10;
  // Depth below which a projection is not used, metres (the triangulation's depth floor).
  double min_depth_m = kMinDepthM;

  Status Check() const;
};

struct TrackExtensionReport {
  int observations_added = 0;  // unassigned junctions joined to a track
  int tracks_merged = 0;       // tracks absorbed into another
  int ambiguous = 0;           // projections with two or more compatible junctions in the gate
  int merges_refused = 0;      // unique candidates in another track that could not be merged
  // Why the other projections (in front, inside the image) found nothing: the gate was wider than
  // max_gate_px; no junction inside it; junctions inside it but none compatible.
  int gate_too_wide = 0, no_junction = 0, incompatible = 0;
  // Why merges were refused: the tracks share a frame; the points disagree.
  // Or the track's point does not find the other track's junction in every one of its frames.
  int merge_overlap = 0, merge_disagree = 0, merge_unexplained = 0;
  // Indices, in the returned landmarks, of the points and lines that gained observations.
  std::vector<int> changed_points, changed_lines;
};

// Extends reconstruction->tracks and reconstruction->landmarks in place, on the poses
// reconstruction->world_T_base (the refined ones) with its calibration's K and base_T_camera and
// its junctions (per frame). The tracks: as BuildTracks made them (ids 0..n-1 in order); the
// landmarks: their points (track_id) and lines (observations naming track views). Afterwards the
// tracks are renumbered in order of their first view, views sorted by frame, landmark observations
// sorted by frame, point track_ids updated; no track holds a frame twice or a junction of another
// track. A projection is searched for when it lies in the box [seen_min, seen_max] of K's pixel
// frame: the image, (0, 0) .. (width - 1, height - 1), or the wider canvas the junctions were
// detected on (the full view, --undistort_full_view: junctions lie outside the image).
void ExtendTracks(const TrackExtensionOptions& options, const Eigen::Vector2d& seen_min,
                  const Eigen::Vector2d& seen_max, Reconstruction* reconstruction,
                  TrackExtensionReport* report);

}  // namespace sfm

// Lines parallel to the motion placed by the scene's dominant directions (issue 19's "Manhattan
// regularisation", docs/tracks_and_triangulation.md, "Lines along the motion"). A segment track
// whose back-projected planes coincide (the line lies in a plane through the camera path, e.g. a
// wall-ceiling edge along a corridor) fixes only that plane; when its junction is a drawn point P
// and exactly one of the scene's three orthogonal dominant directions, through P, agrees with
// every view's image segment, the line is P plus that direction, bounded by the far end-points.
// Runs on the final poses after the wireframe selection: poses and the adjusted map are untouched.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/triangulation_options.h"
#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"
#include "geometry/pose.h"

namespace sfm {

// Three orthonormal dominant directions of the drawn wireframe (columns of `axes`).
struct DominantDirections {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  bool found = false;  // at least two directions each held by inliers
  // The share of the drawn lines' and edges' length within inlier_deg of one of the axes: how far
  // the scene is made of three orthogonal directions (a Manhattan world).
  double support = 0;
  // The inliers' RMS angle from their axis, radians: how far a line counted as along an axis
  // may turn from it, the direction error given to a placed line.
  double sigma_rad = 0;
};

// From the drawn lines (end0 -> end1) and point edges, each weighted by its length: the first axis
// is the direction with the most length within inlier_deg of it (every item's direction tried),
// refined as the principal direction of its inliers' outer products; the second likewise among
// the items within inlier_deg of perpendicular to the first, made orthogonal to it; the third their
// cross product. Degrees, in (0, 45).
DominantDirections EstimateDominantDirections(const Landmarks& drawn, double inlier_deg);

struct ManhattanLineOptions {
  // The pixel noise of the observations (WireframeSelectionReport::pixel_sigma_px) and the poses'
  // error (WireframePoseDrift).
  double pixel_sigma_px = kJunctionLocationErrorPx;
  PoseDrift drift;
  // The chi-square level of the image test (WireframeOptions::consistency_level). In (0, 1).
  double level = 0.999;
  // A segment track is a candidate when its planes spread by at most this (the line
  // triangulation's LineTriangulationOptions::min_plane_angle_deg: what it rejects as unobservable).
  double min_plane_angle_deg = 3.0;
  // Views a candidate needs: its far end-points are tested against one 3D end (max_end_spread_px),
  // which two or three views hardly test. >= 2.
  int min_views = 4;
  // Every view's far end-point must lie within this distance along its segment of the projection of
  // the placed line's end1: the end-point model's spread on generated vertex ends (10 % / 90 %
  // -4.8 / 0.9 px, docs/endpoint_model.md). Pixels, > 0.
  double max_end_spread_px = 5.0;
  // Whether an undistorted pixel lies in the part of the image the segments were detected in (for
  // SeenByStoredImage with the segment detector's border margin). A view's far end-point is at the
  // border when the point border_step_px beyond it along its segment is not: the edge may leave
  // the view there. Empty: no end-point is at the border.
  std::function<bool(const Eigen::Vector2d&)> seen_by_image;
  double border_step_px = 2.0;
  // EstimateDominantDirections' inlier angle, degrees in (0, 45).
  double inlier_deg = 2.0;
  // Lines are placed only when the dominant directions hold at least this share of the drawn
  // length (DominantDirections::support): the data must show a Manhattan scene. In (0, 1].
  double min_support = 0.6;
  // The end bound of the wireframe selection (MaxVertexSigma, with pixel_sigma_px) and the depth
  // floor of the bounded segment (LineTriangulationOptions::min_depth_m).
  WireframeOptions wireframe;
  LineTriangulationOptions line;
};

struct ManhattanLineReport {
  DominantDirections directions;
  int candidates = 0;     // unobservable segment tracks whose junction is a drawn point, no drawn line
  int inconsistent = 0;   // no dominant direction through the point agrees with the image segments
  int ambiguous = 0;      // more than one does (the plane holds two of them)
  int unbounded = 0;      // the far end-points bound no segment in front of the cameras
  int ends_disagree = 0;  // a far end-point beyond max_end_spread_px of end1's projection
  int undetermined = 0;   // the far end's sigma above the wireframe selection's bound
  int placed = 0;         // lines added
  int leaving_view = 0;   // of which bounded by the extent two views see (far ends at the border)
};

// Adds the placed lines to `drawn` (the landmarks SelectWireframeLandmarks kept; before
// AddTopologyEdges, which drops lines lying on an edge between points). A candidate: a segment s of
// the track of a drawn point P (tracks by id, track_id; junctions[frame] indexed by its views,
// CHECKed), with at least two views, none of whose (frame, junction, segment) a drawn line uses,
// whose back-projected planes spread by at most min_plane_angle_deg. For each dominant direction a,
// the line P + t a passes when its distances from the observed p0 and p1 pass the chi-square test
// at `level` with 2n - 2 degrees of freedom (n views; P's own fit takes two); exactly one must
// pass. The segment: when at least two views' far end-points lie inside the image (not at the
// border, seen_by_image), BoundLine's over those views (end0 = P, end1 their median back-projected
// far end-point), whose far end-points must lie within max_end_spread_px of end1's projection;
// otherwise end1 is the second-farthest back-projected far end-point (the extent two views see),
// at least min_depth_m deep in the views that see it. Kept when end1's sigma, sqrt(c^2 + e^2) with
// c = sqrt(sigma_P^2 + (L sigma_rad)^2) across the line (sigma_P: P's PointPositionSigma with the
// drift, L the length) and e = LineEndAlongSigma along it (over the views that see end1), is
// within MaxVertexSigma of end1's smallest depth in those views. Nothing is placed when
// report.directions.support < min_support.
void PlaceManhattanLines(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                         const std::vector<Junctions>& junctions, const std::vector<JunctionTrack>& tracks,
                         const ManhattanLineOptions& options, Landmarks* drawn,
                         ManhattanLineReport* report = nullptr);

}  // namespace sfm

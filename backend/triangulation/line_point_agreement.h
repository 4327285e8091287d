// Lines and points of the drawn wireframe made to agree (docs/tracks_and_triangulation.md, "Lines
// and points agree"): a 3D line whose far end junction is a drawn point ends at that point (the
// vertex shared in wireframe.ply), and a drawn point whose junction lies on a line's image segment
// is fused with the 3D line and splits its edge (a T, or a junction along the line), when the two
// agree within their first-order uncertainties.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/landmarks.h"
#include "frontend/junctions/junction.h"
#include "geometry/pose.h"

namespace sfm {

struct LinePointAgreementOptions {
  // The pixel noise of the landmarks' observations (the wireframe selection's,
  // WireframeSelectionReport::pixel_sigma_px) and the poses' error (WireframePoseDrift).
  double pixel_sigma_px = kJunctionLocationErrorPx;
  PoseDrift drift;
  // A point agrees with a line when its offset d across the line passes the chi-square test at this
  // level with 2 degrees of freedom: d^T (C_P + C_L)^-1 d, C_P the point's covariance
  // (PointPositionCovariance) and C_L the line's there (LinePositionCovariance), both across the
  // line. In (0, 1): the wireframe selection's consistency_level.
  double level = 0.999;
  // A point is the line's far end when, in the median of the line's views, its projection lies
  // along the observed segment from z sqrt(2) sigma before the observed far end-point to this many
  // pixels plus z sqrt(2) sigma beyond it (z the normal quantile at `level`, two-sided): the end-point
  // model's shortfall at the junction detector's threshold, as for the topology edges
  // (TopologyEdgeOptions::max_gap_px). Pixels, >= 0.
  double max_gap_px = 11.0;
};

struct LinePointAgreementReport {
  int candidates = 0;       // (line, point) pairs whose junctions share a detected segment in a frame
  int ends_at_points = 0;   // lines whose far end became a drawn point here
  int points_on_lines = 0;  // points fused with a line (each counted once)
  int splits = 0;           // (line, point) pairs where a line's edge is split at a point
};

// Changes `landmarks` (the drawn ones: SelectWireframeLandmarks, then AddTopologyEdges) in place.
// Candidates: in a frame that observes line L (a junction segment) and point P (a junction other
// than L's), P's junction uses the detected line segment L's segment comes from
// (JunctionSegment::line_segment; junctions[frame], CHECKed). On L's drawn segment S -> E (S its
// junction point or end0, E end1), P's foot at s along it, d across it:
// - far end: when L's end1 is not yet a point, P agrees across and its projections lie at the
//   observed far ends (max_gap_px): end1 = P, end1_point set (the nearest such P along L);
// - interior: when s is between the ends (each at least sqrt(trace(C_P + C_L)) away) and P agrees
//   across: P is appended to L's interior_points (the edge is split there) and fused with L, moved
//   to the inverse-variance mean across the line, x + C_P (C_P + C_L)^-1 d (along the line it
//   keeps its own position). A point on several lines is fused with the one it agrees with best.
// Lines' end1 at points (also those FarEndsAtPoints set) follow the moved points.
void AgreeLinesAndPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                         const std::vector<Junctions>& junctions, const LinePointAgreementOptions& options,
                         Landmarks* landmarks, LinePointAgreementReport* report = nullptr);

}  // namespace sfm

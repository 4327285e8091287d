// Wireframe edges from the junction topology (paper section 4.2): two junctions of a frame that use
// one detected line segment are joined in the scene, so when both junctions' tracks are drawn 3D
// points the segment between the two points is a wireframe edge, whatever its direction to the
// robot's motion (a line along the motion cannot be triangulated as a line, but its end junctions
// can as points). docs/tracks_and_triangulation.md, "Edges from the junction topology".
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "backend/triangulation/landmarks.h"
#include "frontend/junctions/junction.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct TopologyEdgeOptions {
  // The pixel noise of a junction location (the wireframe selection's, WireframeSelectionReport::
  // pixel_sigma_px). A junction segment points at another junction when the other junction lies
  // within 3 sigma of the segment's line, counting both locations' noise and the segment's
  // direction error carried over the distance: 3 sqrt(2) sigma (1 + distance / segment length).
  double pixel_sigma_px = kJunctionLocationErrorPx;
  // Two collinear junction segments pointing at each other may leave this much of the gap between
  // the junctions uncovered: the end-point model's shortfall at the junction detector's threshold,
  // -ln(min_probability) / mu = 3.89 / 0.353 px (docs/endpoint_model.md, JunctionOptions). Pixels.
  double max_gap_px = 11.0;
  // The share of the frames that observe both points in which the image must show the segment.
  // In (0, 1]; 1: every frame.
  double min_support = 1.0;
  // A drawn point lies on an edge (the edge is split there: a T, or a junction along a line) when
  // its distance from the edge is within tan(collinear_deg) of its distance from the nearer end; a
  // line landmark lies on an edge (and is dropped as a duplicate) when both its ends are within
  // tan(collinear_deg) x the edge's length of it. Degrees, in (0, 90).
  double collinear_deg = 2.0;
  // The images place an edge when the planes through it and the centres of the frames observing
  // both ends spread by more than this (the line triangulation's observability rule,
  // LineTriangulationOptions::min_plane_angle_deg). Below it the edge lies in an epipolar plane:
  // any two points of that plane on one image line look joined in every frame, so the join is
  // taken only for an edge within this angle of the baseline (the camera centres' displacement
  // between the first and last of those frames), a line along the motion. Degrees, in (0, 90).
  double min_plane_angle_deg = 3.0;

  Status Check() const {
    if (!(pixel_sigma_px > 0 && std::isfinite(pixel_sigma_px))) {
      return Status::Error("TopologyEdgeOptions: pixel_sigma_px must be finite and > 0");
    }
    if (!(max_gap_px >= 0 && std::isfinite(max_gap_px))) {
      return Status::Error("TopologyEdgeOptions: max_gap_px must be finite and >= 0");
    }
    if (!(min_support > 0 && min_support <= 1))
      return Status::Error("TopologyEdgeOptions: min_support must be in (0, 1]");
    if (!(collinear_deg > 0 && collinear_deg < 90)) {
      return Status::Error("TopologyEdgeOptions: collinear_deg must be in (0, 90)");
    }
    if (!(min_plane_angle_deg > 0 && min_plane_angle_deg < 90)) {
      return Status::Error("TopologyEdgeOptions: min_plane_angle_deg must be in (0, 90)");
    }
    return Status::Ok();
  }
};

struct TopologyEdgeReport {
  int candidates = 0;     // point pairs joined by a segment in some frame
  int unsupported = 0;    // of them, not shown by enough of the frames that observe both points
  int undetermined = 0;   // of the others, in an epipolar plane and not along the baseline
  int edges = 0;          // edges after splitting at points on them and removing duplicates
  int splits = 0;         // points an edge was split at
  int lines_dropped = 0;  // line landmarks lying on an edge
};

// Fills landmarks->point_edges from the junctions of every frame (junctions[frame], indexed by the
// points' observations, CHECKed) and removes from landmarks->lines those lying on one of the new
// edges. A candidate (P, Q): in some frame, P's and Q's junctions are consecutive among the drawn
// points' junctions that use one detected line segment (JunctionSegment::line_segment). It is kept
// when, in at least min_support of the frames that observe both P and Q, their junctions share a
// detected line segment or have junction segments pointing at each other that cover the distance
// between them but for max_gap_px, and the images place it (min_plane_angle_deg, with the camera
// centres of world_T_camera). Kept edges are split at every drawn point lying on them, then
// duplicates are removed. The landmarks are those to draw (SelectWireframeLandmarks).
void AddTopologyEdges(const std::vector<Pose3>& world_T_camera, const std::vector<Junctions>& junctions,
                      const TopologyEdgeOptions& options, Landmarks* landmarks,
                      TopologyEdgeReport* report = nullptr);

}  // namespace sfm

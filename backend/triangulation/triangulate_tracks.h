// Landmarks from tracks: a 3D point per junction track and a 3D line segment per segment track,
// with a status for every one that failed. The entry point of sfm_triangulation.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/triangulation/landmarks.h"
#include "backend/triangulation/line_triangulation.h"
#include "backend/triangulation/point_triangulation.h"
#include "backend/triangulation/triangulation_options.h"
#include "geometry/pose.h"
#include "frontend/junctions/junction.h"
#include "frontend/tracks/tracks.h"

namespace sfm {

struct TriangulationReport {
  std::vector<PointStatus> point_status;             // per junction track, in track order
  std::vector<std::vector<LineStatus>> line_status;  // per junction track, per track segment s

  int Count(PointStatus status) const;  // junction tracks with this status
  int Count(LineStatus status) const;   // segment tracks with this status
};

// A T (a nearer edge cutting a farther one) or an X (two edges crossing) may be an occlusion, not
// a 3D vertex: true when `point` is seen as one in any view (junctions[frame][junction], CHECKed).
bool SeenAsTOrX(const std::vector<Junctions>& junctions, const PointLandmark& point);

// Sets every point's occlusion_candidate by SeenAsTOrX (the floor prior does not hold such points;
// TriangulateTracks sets it on the points it makes).
void MarkOcclusionCandidates(const std::vector<Junctions>& junctions, Landmarks* landmarks);

// Triangulates every track. K: the camera matrix (undistorted pixels); world_T_camera[f] and
// frames[f]: the camera pose (odometry) and the junctions of frame f, one each per frame (CHECKed);
// the tracks must index frames (CHECKed). Per junction track: TriangulatePoint on the junction
// locations; a kOk point becomes a PointLandmark (occlusion_candidate by SeenAsTOrX). Per segment
// track s: TriangulateLine on
// (location, end of segment views[v].segments[s]) over the views where it is not -1, then BoundLine with the
// track's point when it was triangulated; a kOk line becomes a LineLandmark with end0 at the junction end
// (point = end0, direction towards end1) and point_landmark set when the point exists. Landmarks come in
// track order, lines of one track in segment order. options must pass Check() (CHECKed).
Landmarks TriangulateTracks(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                            const std::vector<Junctions>& frames, const std::vector<JunctionTrack>& tracks,
                            const TriangulationOptions& options, TriangulationReport* report = nullptr);

// The points of the tracks that have none in `landmarks` (their triangulation failed on the poses
// they were built on, typically a long track whose reprojection error a drifting start pushed past
// the bound), triangulated again on `world_T_camera` as TriangulateTracks does and appended.
// Returns how many were added. Lines are left as they are.
int TriangulateMissingPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                             const std::vector<Junctions>& frames, const std::vector<JunctionTrack>& tracks,
                             const PointTriangulationOptions& options, Landmarks* landmarks);

}  // namespace sfm

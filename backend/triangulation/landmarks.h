// Landmarks: the 3D points and lines of the map with the image observations they come from. The
// triangulation makes them; bundle adjustment refines them; export writes them.
// Pixels are undistorted pixels (K only); positions are in the world frame, metres.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace sfm {

struct PointObservation {
  int frame = -1;                                   // index into the sequence's frames
  int junction = -1;                                // index into that frame's Junctions
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // the junction location
  // LocationSqrtInformation of the junction: whitens the reprojection error.
  Eigen::Matrix2d sqrt_information = Eigen::Matrix2d::Identity();
};

// One view of a 3D line: a junction segment, from the junction location towards its end-point.
struct LineObservation {
  int frame = -1;
  int junction = -1;  // the junction the segment belongs to
  int segment = -1;   // index of the junction segment within that junction
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero();  // junction location, pixels
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();  // far end-point, pixels
};

struct PointLandmark {
  int track_id = -1;                          // the junction track it was triangulated from
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::vector<PointObservation> observations;  // at most one per frame
  // Seen as a T or an X in some view: possibly an occlusion (a nearer edge crossing a farther
  // one), not a 3D vertex. Set by TriangulateTracks (SeenAsTOrX), which knows the junction types.
  bool occlusion_candidate = false;
};

struct LineLandmark {
  // The infinite 3D line: a point on it and a unit direction.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  // The bounded 3D segment (the junction point at one end where there is one).
  Eigen::Vector3d end0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d end1 = Eigen::Vector3d::Zero();
  int point_landmark = -1;                    // index of the PointLandmark at end0, or -1
  // Set on the drawn landmarks only (FarEndsAtPoints, AgreeLinesAndPoints): the PointLandmark at
  // end1, or -1; and the points lying on the segment, ordered from end0 to end1 (its edge is split
  // at them).
  int end1_point = -1;
  std::vector<int> interior_points;
  std::vector<LineObservation> observations;  // at most one per frame
};

struct Landmarks {
  std::vector<PointLandmark> points;
  std::vector<LineLandmark> lines;
  // 3D segments between two points (indices into `points`, first < second) that the images show
  // joined by one line segment (AddTopologyEdges); only the drawn landmarks have them.
  std::vector<std::pair<int, int>> point_edges;
};

}  // namespace sfm

// Ground truth of a synthetic sequence, and its files under <sequence>/truth/ (format in
// docs/generator.md). True robot poses are the sequence's groundtruth.txt.
//
//   truth/wireframe.txt       the 3D wireframe: "vertex <id> <x> <y> <z>" and
//                             "edge <id> <vertex_a> <vertex_b> <face_a> <face_b>" lines (world, m)
//   truth/wireframe.ply       the same as a PLY line set (SPEC section 3 layout), for viewers
//   truth/scene.txt           the polygons: "face <id> <object> <kind> <albedo> <emission> <grey>
//                             <nx> <ny> <nz> <count> <x y z>..." 
//   truth/frames/NNNNNN.txt   per frame: "camera" world_T_camera; "vertex" visible wireframe
//                             vertices with undistorted and distorted pixels; "segment" visible
//                             parts of wireframe edges
// Numbers are written with 17 significant digits, so they read back exactly.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose.h"
#include "util/status.h"
#include "sequences/generator/scene.h"
#include "sequences/generator/wireframe.h"

namespace sfm {

// Why a visible segment ends where it ends.
enum class SegmentEnd {
  kVertex,     // at the wireframe vertex (the edge's own end)
  kOcclusion,  // something nearer hides the rest: a T junction in the image
  kBorder,     // the image border (or the near plane)
};
const char* SegmentEndName(SegmentEnd end);  // "vertex", "occlusion", "border"

struct VisibleVertex {
  int vertex = -1;                                          // index into Wireframe::vertices
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();          // undistorted image (K only), where junctions are reported
  Eigen::Vector2d pixel_distorted = Eigen::Vector2d::Zero();  // stored image
  double depth = 0;                                         // camera z, m
  int degree = 0;                                           // visible edges that leave it in this frame
  std::string type = "-";  // junction type of those edges: L, Y, ARROW, T, X, N; "-": none (fewer than 2, or 2 collinear)
};

struct VisibleSegment {
  int edge = -1;                                     // index into Wireframe::edges
  double t[2] = {0, 1};                              // ends along the edge: point = a + t (b - a), t[0] < t[1]
  Eigen::Vector2d pixel[2];                          // ends in the undistorted image
  Eigen::Vector2d pixel_distorted[2];                // ends in the stored image
  SegmentEnd end[2] = {SegmentEnd::kVertex, SegmentEnd::kVertex};
};

struct FrameTruth {
  int index = 0;
  double timestamp = 0;  // s
  Pose3 world_T_camera;
  std::vector<VisibleVertex> vertices;  // by increasing vertex index
  std::vector<VisibleSegment> segments;  // by edge index, then t
};

struct GroundTruth {
  Wireframe wireframe;
  std::vector<FrameTruth> frames;
};

// Writes truth/ inside `sequence_dir` (created if needed): wireframe, scene and one file per frame.
Status WriteGroundTruth(const std::string& sequence_dir, const Scene& scene, const GroundTruth& truth);

// Reads truth/wireframe.txt and truth/frames/*.txt of a sequence (the frames 000000, 000001, ...
// up to the first missing one). Fails, naming the file and line, on anything malformed.
Status ReadGroundTruth(const std::string& sequence_dir, GroundTruth* truth);

}  // namespace sfm

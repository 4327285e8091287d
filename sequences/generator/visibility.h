// Which parts of the wireframe one view sees: the per-frame ground truth.
//
// A 3D point is visible when it is in front of the near plane, its distorted pixel lies in the
// stored image, and no face is nearer along its ray. The last test uses the rasterised canvas:
// the faces of the four canvas samples around the point's undistorted pixel are intersected with
// the point's own ray, and the point is hidden when one of them is nearer by more than the
// tolerance (so a point right at an occluding contour counts as hidden: the test is conservative
// by at most one canvas sample). Edges are sampled every `sample_spacing` px of the undistorted
// image; the ends of each visible run are refined by bisection.
#pragma once

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/renderer.h"
#include "sequences/generator/scene.h"
#include "sequences/generator/wireframe.h"

namespace sfm {

struct VisibilityOptions {
  double near = 0.05;                 // m, as the renderer's
  double sample_spacing = 1.0;        // px along an edge in the undistorted image
  double min_segment_length = 2.0;    // px, shorter visible runs are dropped
  double depth_tolerance = 1e-4;      // relative: an occluder must be nearer by this fraction of the depth
  double collinear_tolerance = 0.14;  // rad (8 deg): junction edges this close to a straight angle are collinear
  int bisection_steps = 30;           // refinement of the ends of visible runs
};

// The visible vertices and segments of `wireframe` seen from `world_T_camera`, from the canvas the
// renderer rasterised for that pose. Sets everything in `truth` but index and timestamp.
void ComputeFrameTruth(const Scene& scene, const Wireframe& wireframe, const Camera& camera,
                       const Pose3& world_T_camera, const Canvas& canvas, const VisibilityOptions& options,
                       FrameTruth* truth);

}  // namespace sfm

// 3D points from junction tracks: multi-view linear triangulation, Gauss-Newton refinement of the
// reprojection error, and the checks that reject a point the views do not determine.
// Pixels are undistorted pixels (K only); positions in the world frame, metres.
// H&Z: Hartley and Zisserman, Multiple View Geometry in Computer Vision, 2nd edition (2004).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/triangulation/triangulation_options.h"
#include "geometry/pose.h"

namespace sfm {

// One observation of a point: the camera's pose and the pixel where the point is seen.
struct PointView {
  Pose3 world_T_camera;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

// The outcome of triangulating one track, checks in this order.
enum class PointStatus {
  kOk,
  kTooFewViews,   // fewer than 2 views
  kLowParallax,   // largest angle between viewing rays <= min_parallax_deg (or rays meet at infinity)
  kBehindCamera,  // the point has depth <= 0 in some view
  kLargeReprojectionError,  // some view's reprojection error >= max_reprojection_error_px
  kTooClose,                // the refined point has depth < min_depth_m in some view
};

// "ok", "too_few_views", "low_parallax", "behind_camera", "large_reprojection_error", "too_close".
const char* PointStatusName(PointStatus status);

// Largest angle between the viewing rays of two views (the rays from the camera centres through
// the pixels, as directions in the world), radians in [0, pi].
double MaxRayAngle(const Eigen::Matrix3d& K, const std::vector<PointView>& views);

// Linear (DLT) triangulation of H&Z section 12.2, over all views: each view gives the two rows
// x p3^T - p1^T and y p3^T - p2^T of A in normalised coordinates (K^-1 pixel, P = [R | t] of
// camera_T_world), world coordinates centred on the mean camera centre for conditioning; the point
// is the right singular vector of A's smallest singular value. Returns it homogeneous (world
// frame), so a point at infinity (last coordinate 0) is representable. At least 2 views (CHECKed).
Eigen::Vector4d TriangulateDlt(const Eigen::Matrix3d& K, const std::vector<PointView>& views);

// Gauss-Newton (H&Z appendix A6.1) on the sum of squared reprojection errors in pixels, from
// `point`, at most `iterations` steps; a step that does not lower the cost ends the iteration, so
// the cost never rises. The point must have positive depth in every view (CHECKed).
Eigen::Vector3d RefinePoint(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                            const Eigen::Vector3d& point, int iterations);

// Pixels between the projection of `point` and the observed pixel, per view (inf for depth <= 0).
std::vector<double> ReprojectionErrors(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                                       const Eigen::Vector3d& point);

// The whole point triangulation: too few views, parallax (MaxRayAngle), TriangulateDlt, depth,
// RefinePoint (its steps never cross a camera's z = 0 plane: there the cost is infinite), largest
// reprojection error, depth of the refined point against min_depth_m. `*point` is set when the
// status is kOk.
// options must pass Check() (CHECKed).
PointStatus TriangulatePoint(const Eigen::Matrix3d& K, const std::vector<PointView>& views,
                             const PointTriangulationOptions& options, Eigen::Vector3d* point);

}  // namespace sfm

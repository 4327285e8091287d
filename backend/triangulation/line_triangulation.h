// 3D lines from segment tracks: each view's junction segment back-projects to a plane through the
// camera centre; the planes of all views meet in the 3D line, which the observed end-points bound
// into a 3D segment. Pixels are undistorted pixels (K only); the world frame is in metres.
// H&Z: Hartley and Zisserman, Multiple View Geometry in Computer Vision, 2nd edition (2004).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "backend/triangulation/triangulation_options.h"
#include "geometry/pose.h"

namespace sfm {

// One observation of a line: a junction segment, from the junction location to its far end-point.
struct LineView {
  Pose3 world_T_camera;
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero();  // junction location, pixels
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();  // far end-point, pixels; != p0 (CHECKed)
};

// An infinite 3D line.
struct Line3 {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       // a point on the line, metres
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit
};

// A bounded 3D line segment.
struct Segment3 {
  Eigen::Vector3d end0 = Eigen::Vector3d::Zero();  // the junction end, metres
  Eigen::Vector3d end1 = Eigen::Vector3d::Zero();  // the far end, metres
};

// The outcome of triangulating one segment track, checks in this order.
enum class LineStatus {
  kOk,
  kTooFewViews,             // fewer than 2 views
  kUnobservable,            // largest angle between the views' planes <= min_plane_angle_deg
  kLargeReprojectionError,  // an observed end >= max_reprojection_error_px from the projected line
  kNoExtent,                // the back-projected end-points bound no segment of positive length
  kBehindCamera,            // an end of the bounded segment has depth <= 0 in some view
  kTooClose,                // an end of the bounded segment has depth < min_depth_m in some view
};

// "ok", "too_few_views", "unobservable", "large_reprojection_error", "no_extent", "behind_camera",
// "too_close".
const char* LineStatusName(LineStatus status);

// The plane through the camera centre and the image line through p0 and p1 (H&Z section 8.1.2,
// result 8.2: pi = P^T l with P = K [R | t] of camera_T_world and l = p0 x p1), as (n, d) with
// n . X + d = 0 for world points X and |n| = 1.
Eigen::Vector4d BackProjectedPlane(const Eigen::Matrix3d& K, const LineView& view);

// Largest angle between two of the planes, radians in [0, pi/2] (normals' signs ignored).
double MaxPlaneAngle(const std::vector<Eigen::Vector4d>& planes);

// How far the camera centres spread across the measured planes, as seen from `line`: the largest,
// over views i and j, of asin(|n_i . C_j + d_i| / distance(C_j, line)). For planes that hold the
// line, the angle at the line between the planes through it and C_i and C_j: without noise, the
// same as MaxPlaneAngle. Radians in [0, pi/2]. Noise in the image lines tilts each plane about
// its own centre only, so this stays 0 for coincident centres, where MaxPlaneAngle measures the
// noise, unless the line passes within a few baselines of a centre (which the depth floor
// rejects). planes[i] must belong to centres[i]. A centre on the line counts as pi/2.
double MaxCentreSpreadAngle(const std::vector<Eigen::Vector4d>& planes,
                            const std::vector<Eigen::Vector3d>& centres, const Line3& line);

// The line common to the planes, least squares: the two-dimensional null space of the stacked
// plane equations (H&Z section 3.2.2: a line is the pencil of points annihilated by the planes
// through it) from the SVD, the two right singular vectors of the smallest singular values, with
// the world centred on `centre` for conditioning. At least 2 planes, not all coincident.
Line3 IntersectPlanes(const std::vector<Eigen::Vector4d>& planes, const Eigen::Vector3d& centre);

// Largest distance, over views and over p0 and p1, of an observed end from the image of the line
// (l = K^-T (X_c x d_c) for a point X_c and direction d_c of the line in the camera frame). Pixels.
double LineReprojectionError(const Eigen::Matrix3d& K, const std::vector<LineView>& views, const Line3& line);

// The infinite line of a segment track: too few views, MaxPlaneAngle (kUnobservable),
// IntersectPlanes (centred on the mean camera centre), kTooClose when the line passes within
// min_depth_m of a camera centre (its image there is nearly a point; and where the planes of
// nearly coincident centres meet), MaxCentreSpreadAngle at most min_centre_spread_deg
// (kUnobservable: the planes differ by noise, not by baseline), LineReprojectionError. `*line` is set when the status is kOk.
// options must pass Check() (CHECKed).
LineStatus TriangulateLine(const Eigen::Matrix3d& K, const std::vector<LineView>& views,
                           const LineTriangulationOptions& options, Line3* line);

// Parameter s of the point line.point + s * line.direction nearest to the viewing ray of `pixel`
// (closest points of two lines); nullopt when the ray is within 1e-9 rad of parallel to the line.
std::optional<double> BackProjectOntoLine(const Eigen::Matrix3d& K, const Pose3& world_T_camera,
                                          const Eigen::Vector2d& pixel, const Line3& line);

// Bounds the line into a segment. Every observed end is back-projected onto the line (the point of
// the line nearest to its viewing ray; a ray within 1e-9 rad of parallel to the line is skipped).
// end0: `junction_point` projected onto the line when given (the track's triangulated junction),
// else the median of the back-projected junction locations. end1: the median of the back-projected
// far end-points, the extent seen in a typical view (one view's overshoot, or a far end near the
// line's vanishing point, does not move it). kNoExtent when end1 is not beyond end0 along the
// direction in which the views see the far ends (or nothing could be back-projected);
// kBehindCamera when an end has depth <= 0 in a view; kTooClose when an end has depth below
// options.min_depth_m in a view. `*segment` is set when kOk. options must pass Check() (CHECKed).
LineStatus BoundLine(const Eigen::Matrix3d& K, const std::vector<LineView>& views, const Line3& line,
                     const Eigen::Vector3d* junction_point, const LineTriangulationOptions& options,
                     Segment3* segment);

}  // namespace sfm

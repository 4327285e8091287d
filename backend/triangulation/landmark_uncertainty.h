// How well the views determine a landmark, and whether its observations agree with it, from the
// pixel noise alone: first-order position covariances of a point and of a point of a 3D line, and
// a chi-square test of the reprojection residuals. Used to choose what the wireframe shows
// (wireframe_selection.h); docs/tracks_and_triangulation.md, "Wireframe vertices".
// Pixels are undistorted pixels (K only); positions in the world frame, metres.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/pose.h"

namespace sfm {

// One view of a line: the camera and the observed image segment (junction location p0, far end p1).
struct LineSegmentView {
  Pose3 world_T_camera;
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();
  int frame = 0;  // the frame index: the pose error model's path coordinate (PoseDrift)
};

// The error the final poses still carry, as the determination test sees it. Each camera's rotation
// error is a random walk along the frame index with `rotation_step_rad` per frame (standard
// deviation per axis of one step), so the rotation of view i relative to the first frame f0 that
// sees a landmark has covariance rotation_step_rad^2 min(f_i - f0, f_j - f0) I3 with view j: the
// error is correlated along the path and does not average down over the views as pixel noise does.
// The part common to all views (the rotation at f0) turns the whole landmark rigidly about nearby
// centres, a shift of about depth x angle (millimetres: the trajectory's absolute drift), not the
// landmark's own conditioning; it is left out. The camera centres' error likewise
// (translation_step_m): docs/tracks_and_triangulation.md, "Pose error in the determination test"
// and "Translation drift". Both 0: pixel noise only.
struct PoseDrift {
  PoseDrift() = default;
  explicit PoseDrift(double rotation_step, double translation_step = 0)
      : rotation_step_rad(rotation_step), translation_step_m(translation_step) {}

  double rotation_step_rad = 0;
  // The camera centres' error as the same kind of random walk, metres per axis per frame, relative
  // to f0 likewise (and independent of the rotations'). A view's centre off by dc moves its pixel
  // as the point moving by -dc would.
  double translation_step_m = 0;
};

// Standard deviation, metres, of `point` along its worst-determined direction: the square root of
// the largest eigenvalue of sigma_px^2 (sum_i J_i^T J_i)^-1, J_i the 2x3 derivative of view i's
// pixel by the world point (H&Z section 5.2.4 / A6: the first-order covariance of the
// least-squares triangulation). +infinity when the views leave a direction undetermined (one view,
// or every ray parallel) or the point is not in front of every camera.
double PointPositionSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Eigen::Vector3d& point, double sigma_px);

// The same with the poses' error added: the least-squares triangulation weighs the views by the
// pixel noise alone, so the poses' errors reach the point through its gain
// G_i = (sum J^T J)^-1 J_i^T B_i (B_i the 2x6 derivative of view i's pixel by its camera's
// rotation and centre; -J_i for the centre), Cov = sigma_px^2 (sum J^T J)^-1 + sum_ij G_i C_ij
// G_j^T, C_ij from `drift` with frames[i] the frame of view i (same size as world_T_camera).
double PointPositionSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const std::vector<int>& frames, const Eigen::Vector3d& point, double sigma_px,
                          const PoseDrift& drift);

// The covariance (metres^2, world frame) whose worst direction's square root the PointPositionSigma
// above is. False where that is +infinity (*covariance untouched).
bool PointPositionCovariance(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                             const std::vector<int>& frames, const Eigen::Vector3d& point, double sigma_px,
                             const PoseDrift& drift, Eigen::Matrix3d* covariance);

// Standard deviation, metres, across the line (the worst of the two directions normal to
// `direction`) of the 3D line's position at its point `x`. Each view's image line is fixed by its
// two end-points, each off by sigma_px across the line independently; where x projects at the
// fraction t along p0 -> p1 (t < 0 or > 1: extrapolated), the image line is then off by
// sigma_px * sqrt((1 - t)^2 + t^2) across itself, which moves x only along the view's plane
// normal. The information sum_i g_i g_i^T / var_i (g_i = J_i^T m_i, m_i the image line's unit
// normal) restricted to the plane normal to the line gives a 2x2 covariance. +infinity when the
// planes do not fix both directions (fewer than two views, or all planes one: a line parallel to
// the motion) or x is not in front of every camera.
//
// With `subtract_plane_noise`: the g_i are measured, not true, and their directions (the planes'
// normals) carry the end-points' noise too. For a line whose true planes nearly coincide (a line in
// a plane through the path, a short segment), the measured normals spread by that noise alone, and
// sum_i g_i g_i^T then shows a spread, hence an information, that the geometry does not have. Its
// expected excess, sum_i |g_i|^2 sigma_px^2 (dn0_i dn0_i^T + dn1_i dn1_i^T) / var_i (dnk_i: the
// change of view i's unit plane normal per pixel of its end-point k across the segment), is
// subtracted (the unbiased estimate of the true information, first order); +infinity when nothing
// is left in some direction across the line. docs/tracks_and_triangulation.md, "Plane noise in
// the line sigma".
double LinePositionSigma(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                         const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                         const PoseDrift& drift = PoseDrift(), bool subtract_plane_noise = false);
// With `drift`: a camera's pose error d_i (rotation, centre) moves view i's image line across
// itself, at x's projection, by m_i^T B_i d_i; that reaches x through the same weighted least
// squares as the pixel noise (weights 1 / var_i), and the views' poses are correlated by `drift`
// (views[i].frame).

// The 2 x 2 covariance (metres^2) across the line whose worst direction's square root
// LinePositionSigma is, in the orthonormal basis `plane` (3 x 2, world frame, normal to
// `direction`). False where LinePositionSigma is +infinity.
bool LinePositionCovariance(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                            const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                            const PoseDrift& drift, bool subtract_plane_noise, Eigen::Matrix2d* covariance,
                            Eigen::Matrix<double, 3, 2>* plane);

// Standard deviation, metres, *along* the line of a line end found by back-projection: the point x
// of the 3D line (direction u) where the views' measured pixels (a junction location or a far
// end-point) fall, i.e. s in x + s u fitted in least squares to each view's pixel along its image
// line. View i sees x move along the line at a_i = |J_i u| pixels per metre (J_i the projection's
// Jacobian), so the pixel noise gives var_s = sigma_px^2 / sum a_i^2; and a shift dx of the whole
// line across itself (by `across_sigma`, the line's LinePositionSigma at x, in its worst
// direction) moves the fitted s by g^T dx, g = sum_i a_i J_i^T t_i / sum_i a_i^2 (t_i the image
// line's unit direction) restricted to the plane normal to u: |g| ~ 1 / sin(ray-line angle), the
// reason a line seen nearly end-on places its back-projected ends badly. The line error is one
// for all views, so it is not averaged down. sqrt(var_s + across_sigma^2 |g|^2); +infinity when x
// is not in front of every view or no view sees x move along the line.
double LineEndAlongSigma(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                         const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                         double across_sigma);

// The chi-square statistic of a point's residuals, sum_i |pixel_i - project_i(point)|^2 / sigma_px^2
// (2 per view), and its degrees of freedom 2n - 3. +infinity when the point is behind a camera.
double PointChiSquare(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                      const std::vector<Eigen::Vector2d>& pixels, const Eigen::Vector3d& point,
                      double sigma_px, int* degrees_of_freedom);

// The same for a line: the distances of p0 and p1 from the projected line, over sigma_px, squared
// and summed (2 per view), with 2n - 4 degrees of freedom (a line has 4). +infinity when the line
// passes through a camera centre.
double LineChiSquare(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                     const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double sigma_px,
                     int* degrees_of_freedom);

// The p-quantile of the chi-square distribution with k >= 1 degrees of freedom, p in (0, 1):
// Wilson & Hilferty's cube-root normal approximation (1931), k (1 - 2/(9k) + z sqrt(2/(9k)))^3 with
// z the standard normal p-quantile. At p = 0.999 it is high by 3.0 % for k = 1 (11.16 against
// 10.83), 1.7 % for k = 3, 0.6 % for k = 10: the test is then slightly lenient, never strict.
double ChiSquareQuantile(double p, int k);

}  // namespace sfm

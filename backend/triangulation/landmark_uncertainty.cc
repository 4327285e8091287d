#include "backend/triangulation/landmark_uncertainty.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace sfm {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// d pixel / d world point at `p_camera` (camera frame, z > 0) for the camera with rotation R
// (camera_R_world).
Eigen::Matrix<double, 2, 3> PixelJacobian(const Eigen::Matrix3d& K, const Eigen::Matrix3d& camera_R_world,
                                          const Eigen::Vector3d& p) {
  Eigen::Matrix<double, 2, 3> d_normalised;
  d_normalised << 1 / p.z(), 0, -p.x() / (p.z() * p.z()), 0, 1 / p.z(), -p.y() / (p.z() * p.z());
  return K.topLeftCorner<2, 2>() * d_normalised * camera_R_world;
}

// d pixel / d camera rotation at `p` (camera frame): a small rotation dtheta of the camera moves
// the point to p - dtheta x p in the camera frame (the sign is immaterial for a covariance).
Eigen::Matrix<double, 2, 3> PixelByRotation(const Eigen::Matrix3d& K, const Eigen::Vector3d& p) {
  Eigen::Matrix<double, 2, 3> d_normalised;
  d_normalised << 1 / p.z(), 0, -p.x() / (p.z() * p.z()), 0, 1 / p.z(), -p.y() / (p.z() * p.z());
  Eigen::Matrix3d p_cross;
  p_cross << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
  return K.topLeftCorner<2, 2>() * d_normalised * p_cross;
}

// d pixel / d (camera rotation, camera centre) at `p` (camera frame), 2 x 6: PixelByRotation, and
// -J for the centre (moving the camera by dc moves the point by -dc relative to it).
Eigen::Matrix<double, 2, 6> PixelByPose(const Eigen::Matrix3d& K, const Eigen::Matrix<double, 2, 3>& J,
                                        const Eigen::Vector3d& p) {
  Eigen::Matrix<double, 2, 6> B;
  B << PixelByRotation(K, p), -J;
  return B;
}

// The covariance of one step of PoseDrift's random walk, (rotation, centre) per axis: 6 x 6 diagonal.
Eigen::Matrix<double, 6, 6> StepCovariance(const PoseDrift& drift) {
  Eigen::Matrix<double, 6, 1> diagonal;
  diagonal << Eigen::Vector3d::Constant(drift.rotation_step_rad * drift.rotation_step_rad),
      Eigen::Vector3d::Constant(drift.translation_step_m * drift.translation_step_m);
  return diagonal.asDiagonal();
}

// min(f_i - f0, f_j - f0): the number of random-walk steps two views' poses relative to the first
// frame f0 share, so their covariance is that times StepCovariance.
double SharedSteps(int frame_i, int frame_j, int first_frame) {
  return std::min(frame_i - first_frame, frame_j - first_frame);
}

bool HasDrift(const PoseDrift& drift) {
  return drift.rotation_step_rad != 0 || drift.translation_step_m != 0;
}

// The covariance of a vertex error v = sum_i gain_i e_i (N x 6 gains, e_i view i's pose error
// relative to the first frame f0): Cov(e_i, e_j) = min(f_i - f0, f_j - f0) x one step.
template <int N>
Eigen::Matrix<double, N, N> PoseTerm(const PoseDrift& drift, const std::vector<int>& frames,
                                     const std::vector<Eigen::Matrix<double, N, 6>>& gain) {
  const int first_frame = *std::min_element(frames.begin(), frames.end());
  Eigen::Matrix<double, N, N> covariance = Eigen::Matrix<double, N, N>::Zero();
  const Eigen::Matrix<double, 6, 6> step = StepCovariance(drift);
  for (size_t i = 0; i < frames.size(); ++i) {
    for (size_t j = 0; j < frames.size(); ++j) {
      covariance += SharedSteps(frames[i], frames[j], first_frame) * gain[i] * step * gain[j].transpose();
    }
  }
  return covariance;
}

// The largest eigenvalue's square root of a symmetric matrix.
template <int N>
double WorstSigma(const Eigen::Matrix<double, N, N>& covariance) {
  return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>>(covariance).eigenvalues().maxCoeff()));
}

// The standard normal p-quantile (Acklam's rational approximation, relative error < 1.2e-9).
double NormalQuantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > 1 - low) return -NormalQuantile(1 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

}  // namespace

double PointPositionSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const Eigen::Vector3d& point, double sigma_px) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (const Pose3& camera : world_T_camera) {
    const Pose3 camera_T_world = camera.Inverse();
    const Eigen::Vector3d p = camera_T_world * point;
    if (!(p.z() > 0)) return kInfinity;
    const Eigen::Matrix<double, 2, 3> J = PixelJacobian(K, camera_T_world.RotationMatrix(), p);
    information += J.transpose() * J;
  }
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(information).eigenvalues().minCoeff();
  // Relative to the largest: a rank-deficient information matrix is not inverted.
  if (!(smallest > 1e-12 * information.trace())) return kInfinity;
  return sigma_px / std::sqrt(smallest);
}

double PointPositionSigma(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                          const std::vector<int>& frames, const Eigen::Vector3d& point, double sigma_px,
                          const PoseDrift& drift) {
  CHECK_EQ(world_T_camera.size(), frames.size());
  const double pixel_only = PointPositionSigma(K, world_T_camera, point, sigma_px);
  if (!std::isfinite(pixel_only) || !HasDrift(drift)) return pixel_only;
  Eigen::Matrix3d covariance;
  PointPositionCovariance(K, world_T_camera, frames, point, sigma_px, drift, &covariance);
  return WorstSigma<3>(covariance);
}

bool PointPositionCovariance(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                             const std::vector<int>& frames, const Eigen::Vector3d& point, double sigma_px,
                             const PoseDrift& drift, Eigen::Matrix3d* covariance_out) {
  CHECK_EQ(world_T_camera.size(), frames.size());
  if (!std::isfinite(PointPositionSigma(K, world_T_camera, point, sigma_px))) return false;
  const size_t n = world_T_camera.size();
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  std::vector<Eigen::Matrix<double, 2, 3>> J(n);
  std::vector<Eigen::Matrix<double, 2, 6>> B(n);
  for (size_t i = 0; i < n; ++i) {
    const Pose3 camera_T_world = world_T_camera[i].Inverse();
    const Eigen::Vector3d p = camera_T_world * point;  // z > 0: pixel_only is finite
    J[i] = PixelJacobian(K, camera_T_world.RotationMatrix(), p);
    B[i] = PixelByPose(K, J[i], p);
    information += J[i].transpose() * J[i];
  }
  const Eigen::Matrix3d inverse = information.inverse();
  std::vector<Eigen::Matrix<double, 3, 6>> gain(n);
  for (size_t i = 0; i < n; ++i) gain[i] = inverse * J[i].transpose() * B[i];
  *covariance_out = sigma_px * sigma_px * inverse;
  if (HasDrift(drift)) *covariance_out += PoseTerm<3>(drift, frames, gain);
  return true;
}

namespace {

// The covariance of view's unit plane normal (world frame, the plane through the camera centre and
// the image line p0 p1) when each end-point moves across the segment (along `normal`, the image
// line's unit normal) by independent noise of sigma_px: sigma_px^2 (dn0 dn0^T + dn1 dn1^T), dnk the
// first-order change of the normal per pixel of end k. The camera-frame normal is m / |m| with m =
// K^T (p0~ x p1~) (BackProjectedPlane).
Eigen::Matrix3d PlaneNormalNoise(const Eigen::Matrix3d& K, const LineSegmentView& view,
                                 const Eigen::Vector2d& normal, double sigma_px) {
  const Eigen::Vector3d p0 = view.p0.homogeneous(), p1 = view.p1.homogeneous();
  const Eigen::Vector3d shift(normal.x(), normal.y(), 0);
  const Eigen::Vector3d m = K.transpose() * p0.cross(p1);
  const double length = m.norm();
  const Eigen::Vector3d n = m / length;
  const Eigen::Matrix3d project = Eigen::Matrix3d::Identity() - n * n.transpose();
  const Eigen::Matrix3d world_R_camera = view.world_T_camera.RotationMatrix();
  const Eigen::Vector3d dn0 = world_R_camera * project * (K.transpose() * shift.cross(p1)) / length;
  const Eigen::Vector3d dn1 = world_R_camera * project * (K.transpose() * p0.cross(shift)) / length;
  return sigma_px * sigma_px * (dn0 * dn0.transpose() + dn1 * dn1.transpose());
}

// LinePositionSigma's computation: false when the views do not fix both directions across the line
// (+infinity), else the pixel-noise sigma (worst direction) and, with `covariance`, the 2 x 2
// covariance across the line, with the poses' drift, in the basis `plane` (3 x 2, orthonormal,
// normal to the line).
bool LineAcross(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views, const Eigen::Vector3d& x,
                const Eigen::Vector3d& direction, double sigma_px, const PoseDrift& drift,
                bool subtract_plane_noise, double* pixel_sigma, Eigen::Matrix2d* covariance,
                Eigen::Matrix<double, 3, 2>* plane_out) {
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  // Per view: g_i / var_i (the weighted gain's direction) and m_i^T B_i (the pose's shift of the
  // image line across itself at x's projection).
  std::vector<Eigen::Vector3d> weighted_gradient;
  std::vector<Eigen::Matrix<double, 1, 6>> line_by_pose;
  for (const LineSegmentView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d p = camera_T_world * x;
    if (!(p.z() > 0)) return false;
    const Eigen::Vector2d pixel = (K * p).hnormalized();
    const Eigen::Vector2d along = view.p1 - view.p0;
    CHECK_GT(along.squaredNorm(), 0) << "a line view needs p0 != p1";
    const double t = (pixel - view.p0).dot(along) / along.squaredNorm();
    const Eigen::Vector2d normal = Eigen::Vector2d(-along.y(), along.x()).normalized();
    const Eigen::Matrix<double, 2, 3> J = PixelJacobian(K, camera_T_world.RotationMatrix(), p);
    const Eigen::Vector3d g = J.transpose() * normal;
    const double variance = (1 - t) * (1 - t) + t * t;
    information += g * g.transpose() / variance;
    if (subtract_plane_noise)
      information -= g.squaredNorm() * PlaneNormalNoise(K, view, normal, sigma_px) / variance;
    weighted_gradient.push_back(g / variance);
    line_by_pose.push_back(normal.transpose() * PixelByPose(K, J, p));
  }
  const Eigen::Vector3d u = direction.normalized();
  const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
  Eigen::Matrix<double, 3, 2> plane;
  plane << a, b;
  const Eigen::Matrix2d across = plane.transpose() * information * plane;
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(across).eigenvalues().minCoeff();
  if (!(smallest > 1e-12 * across.trace())) return false;
  *pixel_sigma = sigma_px / std::sqrt(smallest);
  if (plane_out != nullptr) *plane_out = plane;
  if (covariance == nullptr) return true;
  const Eigen::Matrix2d inverse = across.inverse();
  *covariance = sigma_px * sigma_px * inverse;
  if (!HasDrift(drift)) return true;
  // x's shift across the line from view i's pose error d_i (rotation, centre):
  // inverse P^T (g_i / var_i) (m_i^T B_i) d_i.
  std::vector<Eigen::Matrix<double, 2, 6>> gain;
  for (size_t i = 0; i < views.size(); ++i) {
    gain.push_back(inverse * plane.transpose() * weighted_gradient[i] * line_by_pose[i]);
  }
  std::vector<int> frames;
  for (const LineSegmentView& view : views) frames.push_back(view.frame);
  *covariance += PoseTerm<2>(drift, frames, gain);
  return true;
}

}  // namespace

double LinePositionSigma(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                         const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                         const PoseDrift& drift, bool subtract_plane_noise) {
  double pixel_sigma = kInfinity;
  Eigen::Matrix2d covariance;
  if (!LineAcross(K, views, x, direction, sigma_px, drift, subtract_plane_noise, &pixel_sigma,
                  HasDrift(drift) ? &covariance : nullptr, nullptr))
    return kInfinity;
  return HasDrift(drift) ? WorstSigma<2>(covariance) : pixel_sigma;
}

bool LinePositionCovariance(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                            const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                            const PoseDrift& drift, bool subtract_plane_noise, Eigen::Matrix2d* covariance,
                            Eigen::Matrix<double, 3, 2>* plane) {
  double pixel_sigma = kInfinity;
  return LineAcross(K, views, x, direction, sigma_px, drift, subtract_plane_noise, &pixel_sigma, covariance,
                    plane);
}

double LineEndAlongSigma(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                         const Eigen::Vector3d& x, const Eigen::Vector3d& direction, double sigma_px,
                         double across_sigma) {
  const Eigen::Vector3d u = direction.normalized();
  double speed_squared = 0;                            // sum_i a_i^2
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();  // sum_i a_i J_i^T t_i
  for (const LineSegmentView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d p = camera_T_world * x;
    if (!(p.z() > 0)) return kInfinity;
    const Eigen::Matrix<double, 2, 3> J = PixelJacobian(K, camera_T_world.RotationMatrix(), p);
    const Eigen::Vector2d image_step = J * u;  // pixels per metre along the line
    const double speed = image_step.norm();
    if (!(speed > 0)) continue;  // seen exactly end-on: this view places nothing along the line
    speed_squared += speed * speed;
    weighted += speed * J.transpose() * (image_step / speed);
  }
  if (!(speed_squared > 0) || !std::isfinite(across_sigma)) return kInfinity;
  const Eigen::Vector3d gain = weighted / speed_squared;
  const Eigen::Vector3d gain_across = gain - gain.dot(u) * u;  // g.u = 1: x's own slide along the line
  return std::sqrt(sigma_px * sigma_px / speed_squared +
                   across_sigma * across_sigma * gain_across.squaredNorm());
}

double PointChiSquare(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera,
                      const std::vector<Eigen::Vector2d>& pixels, const Eigen::Vector3d& point,
                      double sigma_px, int* degrees_of_freedom) {
  CHECK_EQ(world_T_camera.size(), pixels.size());
  *degrees_of_freedom = 2 * static_cast<int>(pixels.size()) - 3;
  double sum = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d p = world_T_camera[i].Inverse() * point;
    if (!(p.z() > 0)) return kInfinity;
    sum += ((K * p).hnormalized() - pixels[i]).squaredNorm();
  }
  return sum / (sigma_px * sigma_px);
}

double LineChiSquare(const Eigen::Matrix3d& K, const std::vector<LineSegmentView>& views,
                     const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double sigma_px,
                     int* degrees_of_freedom) {
  *degrees_of_freedom = 2 * static_cast<int>(views.size()) - 4;
  const Eigen::Matrix3d K_inverse_transpose = K.inverse().transpose();
  double sum = 0;
  for (const LineSegmentView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d l =
        K_inverse_transpose * (camera_T_world * point).cross(camera_T_world.rotation * direction);
    const double scale = l.head<2>().norm();
    if (!(scale > 0)) return kInfinity;
    const double e0 = l.dot(view.p0.homogeneous()) / scale, e1 = l.dot(view.p1.homogeneous()) / scale;
    sum += e0 * e0 + e1 * e1;
  }
  return sum / (sigma_px * sigma_px);
}

double ChiSquareQuantile(double p, int k) {
  CHECK(p > 0 && p < 1) << p;
  CHECK_GE(k, 1);
  const double h = 2.0 / (9.0 * k);
  const double cube_root = 1 - h + NormalQuantile(p) * std::sqrt(h);
  return k * cube_root * cube_root * cube_root;
}

}  // namespace sfm

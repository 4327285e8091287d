// What odometry says about two views beyond F: the relative camera pose and its first-order
// uncertainty (docs/matching.md, "Pose uncertainty and cheirality"). Used by MatchJunctions for a
// per-pair epipolar search band (3 sigma of the epipolar distance, instead of a fixed R) and for
// the cheirality test (a match must triangulate in front of camera 1 and 2).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "geometry/pose.h"

namespace sfm {

struct PairGeometry {
  // Intrinsics of both (undistorted) images.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  // p2 = R p1 + t for p1 in camera 1's and p2 in camera 2's coordinates (metres).
  Pose3 camera2_T_camera1;
  // Covariance of the perturbation xi = (omega, dt): the true pose is (Exp(omega) R, t + dt), omega
  // in radians (camera 2's axes), dt in metres. Positive semi-definite.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();

  // x2^T F x1 = 0, F = K^-T [t]x R K^-1: the same F (and scale) as FundamentalFromPoses.
  Eigen::Matrix3d Fundamental() const;
  // dF/dxi_k (k = 0..5) times the square root of the covariance: F(xi) ~ F + sum_k z_k G_k with z_k
  // independent standard normal, so the residual e = x2^T F x1 has variance sum_k (x2^T G_k x1)^2.
  void FundamentalDeviations(Eigen::Matrix3d G[6]) const;
};

// The two odometry poses with sequence.yaml's noise model (docs/formats.md): translation_sigma is
// a fraction of the distance travelled, rotation_sigma radians per frame. Read as wheel odometry's
// errors on the base increment base1_T_base2 = (Exp(w) R_B, t_B + dt), accumulated over the
// frames between the two poses as a random walk: w has per-axis variance frames_apart *
// rotation_sigma^2; dt has standard deviation translation_sigma |t_B| along t_B (wheel radius and
// slip change the distance) and sqrt(frames_apart) rotation_sigma |t_B| across it (the direction
// of travel is as uncertain as the heading over the interval). Propagated through base_T_camera to
// camera2_T_camera1 (numerical Jacobian). frames_apart >= 1.
PairGeometry PairGeometryFromOdometry(const Eigen::Matrix3d& K, const Pose3& base_T_camera,
                                      const Pose3& world_T_base1, const Pose3& world_T_base2,
                                      double translation_sigma, double rotation_sigma, int frames_apart);

// The same two views with their roles swapped (camera1_T_camera2 and its covariance, to first order).
PairGeometry InversePairGeometry(const PairGeometry& geometry);

// Standard deviations (pixels) of the distance of x1 from the epipolar line of x2 (in_image1) and
// of x2 from that of x1 (in_image2) due to the pose uncertainty alone, to first order about
// geometry's pose. +infinity where a line is undefined (a point at an epipole).
struct EpipolarDistanceSigmas {
  double in_image1 = 0;
  double in_image2 = 0;
};
EpipolarDistanceSigmas EpipolarSigmas(const PairGeometry& geometry, const Eigen::Vector2d& x1,
                                      const Eigen::Vector2d& x2);

// The search band of a pair: num_sigmas * sqrt(sigma_pose^2 + 2 location_sigma^2) in each image
// (both locations' errors move the distance).
// Inline: it runs for every pair that reaches the band test.
inline double EpipolarBand(double pose_sigma_px, double location_sigma_px, double num_sigmas) {
  return num_sigmas * std::sqrt(pose_sigma_px * pose_sigma_px + 2 * location_sigma_px * location_sigma_px);
}

// Cheirality (first order): as the depth of x1 falls from infinity, its image in camera 2 leaves
// v2 = K R K^-1 x1 (the point at infinity of the ray) along the epipolar line in the direction
// w2 = K-image of t_xy - m_xy t_z (m = R K^-1 x1 normalised); a point in front of camera 1 lies on
// that side of v2. Fails when x2 lies on the other side of v2 by more than num_sigmas * sqrt(
// sigma_v^2 + 2 location_sigma^2), sigma_v the spread of v2 along w2 under the rotation
// uncertainty; and the same in image 1 with the inverse pose. Not tested (passes) where the ray of
// x1 points behind camera 2 or w2 vanishes (x1 at the epipole, no translation).
bool PassesCheirality(const PairGeometry& geometry, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                      double num_sigmas, double location_sigma_px);

// The part of ParallaxInImage2 that depends on x1 only: parallax = (x2 - v2) . direction.
struct ParallaxFrame {
  bool tested = false;  // false: the ray points behind camera 2, or w2 vanishes
  Eigen::Vector2d v = Eigen::Vector2d::Zero();          // v2, pixels
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  // unit w2
  double sigma = 0;                                     // spread of v2 along w2, pixels
  // The image of the point at depth Z (camera 1) on the ray of x1 is v2 + direction * scale *
  // q / (ray_z + q t_z), q = 1/Z, t_z camera2_T_camera1's translation z: scale = |w2| (pixels per
  // unit of that fraction), ray_z the z of R K^-1 x1 (with K^-1 x1 = (x, y, 1)).
  double scale = 0;
  double ray_z = 0;
};
ParallaxFrame ParallaxFrameOf(const PairGeometry& geometry, const Eigen::Vector2d& x1);

// Signed parallax of x2 beyond v2 along w2 (pixels; negative: behind camera 1) and its pose sigma,
// the quantities PassesCheirality tests in image 2. parallax = 0, sigma = infinity when untested.
struct Parallax {
  double parallax = 0;
  double sigma = 0;
};
Parallax ParallaxInImage2(const PairGeometry& geometry, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2);

}  // namespace sfm

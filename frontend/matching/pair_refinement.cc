#include "frontend/matching/pair_refinement.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <glog/logging.h>

namespace sfm {
namespace {

// Tuning constant of the Cauchy loss for 95 % asymptotic efficiency under Gaussian noise (in
// units of the residual's sigma): the usual choice, e.g. Holland & Welsch 1977.
constexpr double kCauchyConstant = 2.3849;
// Chi-square 99 % quantiles for 1..6 degrees of freedom: the prior consistency gate at the same
// level as the 99 % gate of each match.
constexpr double kChiSquare99[6] = {6.635, 9.210, 11.345, 13.277, 15.086, 16.812};
// Iterations of reweighted Gauss-Newton; the benchmark pairs converge in about 10 (docs/matching.md),
// the limit only bounds the cost.
constexpr int kMaxIterations = 30;

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Jacobian = Eigen::Matrix<double, Eigen::Dynamic, 6>;

// Left Jacobian of SO(3): Exp(omega + delta) = Exp(J_l(omega) delta) Exp(omega) to first order.
Eigen::Matrix3d LeftJacobian(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  const Eigen::Matrix3d W = Cross(omega);
  if (angle < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * W;
  const double angle2 = angle * angle;
  return Eigen::Matrix3d::Identity() + (1 - std::cos(angle)) / angle2 * W +
         (angle - std::sin(angle)) / (angle2 * angle) * W * W;
}

// The state: z, the perturbation xi = (omega, dt) = A z of the prior pose in whitened coordinates
// (A A^T = prior covariance), so the prior term is |z|^2. A's columns are zero along directions the
// prior fixes, so those components of z get no gradient and stay 0. The pose at z is
// (Exp(omega) R, t + dt), PairGeometry's convention.
class PoseModel {
 public:
  PoseModel(const PairGeometry& prior, const Matrix6& A) : prior_(prior), A_(A), K_inverse_(prior.K.inverse()) {}

  Pose3 PoseAt(const Vector6& z) const {
    const Vector6 xi = A_ * z;
    const Eigen::Vector3d omega = xi.head<3>();
    const double angle = omega.norm();
    const Eigen::Matrix3d exp_omega =
        angle > 0 ? Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    return Pose3(Eigen::Matrix3d(exp_omega * prior_.camera2_T_camera1.RotationMatrix()),
                 prior_.camera2_T_camera1.translation + xi.tail<3>());
  }

  // F at z and, when D is not null, dF/dxi_j (j = 0..5): K^-T [t]x [J_l e_j]x R K^-1 for the
  // rotation, K^-T [e_j]x R K^-1 for the translation.
  Eigen::Matrix3d FundamentalAt(const Vector6& z, Eigen::Matrix3d* D = nullptr) const {
    const Pose3 pose = PoseAt(z);
    const Eigen::Matrix3d R = pose.RotationMatrix();
    const Eigen::Matrix3d right = R * K_inverse_;
    const Eigen::Matrix3d left = K_inverse_.transpose() * Cross(pose.translation);
    if (D != nullptr) {
      const Eigen::Matrix3d J_l = LeftJacobian((A_ * z).head<3>());
      for (int j = 0; j < 3; ++j) {
        D[j] = left * Cross(J_l.col(j)) * right;
        D[3 + j] = K_inverse_.transpose() * Cross(Eigen::Vector3d::Unit(j)) * right;
      }
    }
    return left * right;
  }

  const Matrix6& A() const { return A_; }

 private:
  const PairGeometry& prior_;
  const Matrix6& A_;
  Eigen::Matrix3d K_inverse_;
};

// Residuals r and their Jacobian J (n x 6) with respect to z. r = e / s with e = x2^T F x1 and
// s^2 = |(F x1)_xy|^2 + |(F^T x2)_xy|^2, so dr = de / s - e ds / s^2.
void Linearise(const PoseModel& model, const Vector6& z, const std::vector<Eigen::Vector2d>& x1,
               const std::vector<Eigen::Vector2d>& x2, Eigen::VectorXd* r, Jacobian* J) {
  Eigen::Matrix3d D[6];
  const Eigen::Matrix3d F = model.FundamentalAt(z, D);
  const Eigen::Index n = static_cast<Eigen::Index>(x1.size());
  r->resize(n);
  Jacobian J_xi(n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d h1 = x1[static_cast<size_t>(i)].homogeneous();
    const Eigen::Vector3d h2 = x2[static_cast<size_t>(i)].homogeneous();
    const Eigen::Vector3d line2 = F * h1;
    const Eigen::Vector3d line1 = F.transpose() * h2;
    const double s2 = line2.head<2>().squaredNorm() + line1.head<2>().squaredNorm();
    if (!(s2 > 0)) {
      (*r)(i) = 0;
      J_xi.row(i).setZero();
      continue;
    }
    const double s = std::sqrt(s2);
    const double e = h2.dot(line2);
    (*r)(i) = e / s;
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d d2 = D[j] * h1;
      const Eigen::Vector3d d1 = D[j].transpose() * h2;
      const double ds = (line2.head<2>().dot(d2.head<2>()) + line1.head<2>().dot(d1.head<2>())) / s;
      J_xi(i, j) = h2.dot(d2) / s - e * ds / s2;
    }
  }
  *J = J_xi * model.A();
}

// The robust objective of one round: |z|^2 + sum_i (c_i / sigma)^2 log(1 + (r_i / c_i)^2), i.e.
// the negative log-posterior with a Cauchy likelihood of scale c_i, in units where the location
// noise sigma is 1.
double Cost(const Vector6& z, const Eigen::VectorXd& r, const Eigen::VectorXd& c, double sigma) {
  double cost = z.squaredNorm();
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    cost += (c(i) * c(i)) / (sigma * sigma) * std::log1p((r(i) / c(i)) * (r(i) / c(i)));
  }
  return cost;
}

// Predicted standard deviation of each residual: location noise plus the state's uncertainty.
Eigen::VectorXd ResidualSigmas(const Jacobian& J, const Matrix6& covariance, double sigma) {
  return ((J * covariance).cwiseProduct(J).rowwise().sum().array() + sigma * sigma).sqrt().matrix();
}

}  // namespace

double SampsonDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  const Eigen::Vector3d line2 = F * x1.homogeneous();
  const Eigen::Vector3d line1 = F.transpose() * x2.homogeneous();
  const double norm_squared = line2.head<2>().squaredNorm() + line1.head<2>().squaredNorm();
  if (!(norm_squared > 0)) return 0;
  return x2.homogeneous().dot(line2) / std::sqrt(norm_squared);
}

PairRefinement RefinePairGeometry(const PairGeometry& prior, const std::vector<Eigen::Vector2d>& x1,
                                  const std::vector<Eigen::Vector2d>& x2, const PairRefinementSettings& settings) {
  CHECK_EQ(x1.size(), x2.size());
  CHECK(settings.location_sigma_px > 0 && settings.gate_sigmas > 0 && settings.min_inliers >= 0);
  PairRefinement result;
  result.geometry = prior;
  result.matches = static_cast<int>(x1.size());

  // Whitening of the prior: covariance = V diag(l) V^T, A = V_kept diag(sqrt(l_kept)). Directions
  // with no variance (below 1e-12 of the largest) are held at the prior.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(prior.covariance);
  const double largest = solver.eigenvalues().maxCoeff();
  std::vector<int> kept;
  for (int k = 0; k < 6; ++k) {
    if (largest > 0 && solver.eigenvalues()(k) > 1e-12 * largest) kept.push_back(k);
  }
  if (kept.empty()) {
    result.outcome = PairRefinement::Outcome::kNoPriorUncertainty;
    return result;
  }
  if (result.matches < settings.min_inliers) {
    result.outcome = PairRefinement::Outcome::kTooFewMatches;
    return result;
  }
  const int m = static_cast<int>(kept.size());
  Matrix6 A = Matrix6::Zero();
  for (const int k : kept) A.col(k) = solver.eigenvectors().col(k) * std::sqrt(solver.eigenvalues()(k));
  const PoseModel model(prior, A);
  const double sigma = settings.location_sigma_px;

  // Iteratively reweighted Gauss-Newton with graduated scales: every residual's Cauchy scale is
  // its predicted sigma under the current uncertainty of the estimate (the prior's at first, so
  // the odometry's own error does not count as an outlier); as the posterior shrinks, the scales
  // shrink towards the location noise alone and the wrong matches lose their weight.
  Vector6 z = Vector6::Zero();
  Matrix6 covariance = Matrix6::Identity();
  Vector6 z_new;
  Eigen::VectorXd r, r_new;
  Jacobian J, J_new;
  Linearise(model, z, x1, x2, &r, &J);
  Eigen::VectorXd scales = ResidualSigmas(J, covariance, sigma);
  auto normal_matrix = [&](const Eigen::VectorXd& c, Eigen::VectorXd* w) {
    *w = (1.0 + (r.array() / c.array()).square()).inverse().matrix();
    return Matrix6(Matrix6::Identity() + J.transpose() * w->asDiagonal() * J / (sigma * sigma));
  };
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    // The Gauss-Newton system of the robust objective at fixed scales (IRLS weights w).
    const Eigen::VectorXd c = kCauchyConstant * scales;
    Eigen::VectorXd w;
    const Matrix6 H = normal_matrix(c, &w);
    const Eigen::LDLT<Matrix6> H_ldlt(H);
    const Vector6 g = z + J.transpose() * (w.array() * r.array()).matrix() / (sigma * sigma);
    Vector6 dz = -H_ldlt.solve(g);
    // Backtracking: the objective is not quadratic (Sampson distances, Cauchy loss). The full step
    // is nearly always taken, so the trial point is linearised at once.
    const double cost = Cost(z, r, c, sigma);
    bool improved = false;
    for (int halving = 0; halving < 20 && !improved; ++halving, dz /= 2) {
      z_new = z + dz;
      Linearise(model, z_new, x1, x2, &r_new, &J_new);
      improved = Cost(z_new, r_new, c, sigma) <= cost;
    }
    if (!improved) break;
    z.swap(z_new);
    r.swap(r_new);
    J.swap(J_new);
    ++result.iterations;
    covariance = H_ldlt.solve(Matrix6::Identity());
    const Eigen::VectorXd new_scales = ResidualSigmas(J, covariance, sigma);
    const double scale_change = ((new_scales - scales).array() / scales.array()).abs().maxCoeff();
    scales = new_scales;
    // Converged when the step is below a hundredth of the posterior's standard deviation along it
    // (dz^T H dz, the squared Newton decrement) and no residual's scale moved by 1 %.
    if (dz.dot(H * dz) < 1e-4 && scale_change < 1e-2) break;
  }
  // The posterior at the estimate.
  {
    Eigen::VectorXd w;
    covariance = normal_matrix(kCauchyConstant * scales, &w).ldlt().solve(Matrix6::Identity());
    scales = ResidualSigmas(J, covariance, sigma);
  }

  result.inlier.resize(x1.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    result.inlier[static_cast<size_t>(i)] = std::abs(r(i)) <= settings.gate_sigmas * scales(i);
    result.inliers += result.inlier[static_cast<size_t>(i)] ? 1 : 0;
  }
  result.prior_distance_squared = z.squaredNorm();
  result.prior_gate = kChiSquare99[m - 1];
  if (result.inliers < settings.min_inliers) {
    result.outcome = PairRefinement::Outcome::kTooFewInliers;
    return result;
  }
  if (result.prior_distance_squared > result.prior_gate) {
    result.outcome = PairRefinement::Outcome::kInconsistentWithPrior;
    return result;
  }
  result.outcome = PairRefinement::Outcome::kRefined;
  result.geometry.camera2_T_camera1 = model.PoseAt(z);
  const Matrix6 refined_covariance = A * covariance * A.transpose();
  result.geometry.covariance = 0.5 * (refined_covariance + refined_covariance.transpose());
  return result;
}

}  // namespace sfm

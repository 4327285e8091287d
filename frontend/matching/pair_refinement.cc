#include "frontend/matching/pair_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <glog/logging.h>

namespace sfm {
namespace {

// Tuning constant of the Cauchy loss for 95 % asymptotic efficiency under Gaussian noise (in
// units of the residual's sigma): the usual choice, e.g. Holland & Welsch 1977.
constexpr double kCauchyConstant = 2.3849;
// Iterations of reweighted Gauss-Newton; the benchmark pairs converge in about 10 (docs/matching.md),
// the limit only bounds the cost.
constexpr int kMaxIterations = 30;
// Sample size of the hypotheses: the degrees of freedom of an epipolar geometry with known K (the
// prior fills in the rest).
constexpr int kSampleSize = 5;
// Gauss-Newton steps for a sample's fit: from the prior, five matches need two or three.
constexpr int kSampleIterations = 3;
// Bound on the number of samples (the adaptive count reaches it below an inlier share of 0.47;
// it only bounds the cost).
constexpr int kMaxSamples = 200;
// A fixed seed: the same matches give the same pose, run to run.
constexpr unsigned kSamplingSeed = 1;

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Vector3d LogRotation(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd angle_axis(R);
  return angle_axis.angle() * angle_axis.axis();
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

// Residuals only (for scoring hypotheses).
void Residuals(const PoseModel& model, const Vector6& z, const std::vector<Eigen::Vector2d>& x1,
               const std::vector<Eigen::Vector2d>& x2, Eigen::VectorXd* r) {
  const Eigen::Matrix3d F = model.FundamentalAt(z);
  r->resize(static_cast<Eigen::Index>(x1.size()));
  for (size_t i = 0; i < x1.size(); ++i) {
    const Eigen::Vector3d line2 = F * x1[i].homogeneous();
    const Eigen::Vector3d line1 = F.transpose() * x2[i].homogeneous();
    const double s2 = line2.head<2>().squaredNorm() + line1.head<2>().squaredNorm();
    (*r)(static_cast<Eigen::Index>(i)) = s2 > 0 ? x2[i].homogeneous().dot(line2) / std::sqrt(s2) : 0;
  }
}

// The negative log-posterior of the mixture model "a match is right (Gaussian Sampson distance of
// sigma) or wrong (uniform)", up to constants: |z|^2 + sum_i min((r_i / sigma)^2, gate^2), the
// truncated quadratic of MSAC (Torr & Zisserman 2000) with the prior term. Unlike the Cauchy loss,
// whose cost keeps growing (logarithmically) with the residual, a wrong match costs the same
// wherever it lies outside the gate, so moving the pose to bring a group of wrong matches a few
// pixels closer gains nothing unless they come inside the gate.
double TruncatedCost(const Vector6& z, const Eigen::VectorXd& r, double sigma, double gate) {
  return z.squaredNorm() + (r.array() / sigma).square().min(gate * gate).sum();
}

// Gauss-Newton with backtracking on |z|^2 + sum_i (r_i / sigma)^2 over the given matches, from z.
Vector6 GaussNewton(const PoseModel& model, const std::vector<Eigen::Vector2d>& x1,
                    const std::vector<Eigen::Vector2d>& x2, Vector6 z, double sigma, int max_steps, int* steps,
                    Matrix6* covariance = nullptr) {
  Eigen::VectorXd r, r_new;
  Jacobian J, J_new;
  Linearise(model, z, x1, x2, &r, &J);
  Matrix6 H = Matrix6::Identity() + J.transpose() * J / (sigma * sigma);
  for (int step = 0; step < max_steps; ++step) {
    const Vector6 g = z + J.transpose() * r / (sigma * sigma);
    Vector6 dz = -H.ldlt().solve(g);
    const double cost = z.squaredNorm() + r.squaredNorm() / (sigma * sigma);
    bool improved = false;
    Vector6 z_new;
    for (int halving = 0; halving < 20 && !improved; ++halving, dz /= 2) {
      z_new = z + dz;
      Linearise(model, z_new, x1, x2, &r_new, &J_new);
      improved = z_new.squaredNorm() + r_new.squaredNorm() / (sigma * sigma) <= cost;
    }
    if (!improved) break;
    ++*steps;
    const double decrement = dz.dot(H * dz);
    z = z_new;
    r.swap(r_new);
    J.swap(J_new);
    H = Matrix6::Identity() + J.transpose() * J / (sigma * sigma);
    if (decrement < 1e-4) break;
  }
  if (covariance != nullptr) *covariance = H.ldlt().solve(Matrix6::Identity());
  return z;
}

// A local minimum of TruncatedCost found by majorise-minimise: the matches within the gate at the
// current estimate (gate times each residual's predicted sigma, so an imprecise start still
// collects the right matches) are fitted with the prior by Gauss-Newton, then selected again,
// until the set stops changing.
struct Fit {
  Vector6 z = Vector6::Zero();
  Matrix6 covariance = Matrix6::Identity();  // Laplace, over the final inlier set
  double cost = std::numeric_limits<double>::infinity();  // TruncatedCost
  int inliers = 0;
  int iterations = 0;
};

// Consensus: with a finite `radius_squared` the steps are kept inside the ball |z|^2 <= radius_squared (the
// prior's 99 % ellipsoid in whitened coordinates): a step that would leave it is halved until it
// does not, so from a start inside, the result is a local minimum of the truncated objective over
// the poses the prior admits (step 3 of RefinePairGeometry).
Fit Consensus(const PoseModel& model, const std::vector<Eigen::Vector2d>& x1, const std::vector<Eigen::Vector2d>& x2,
              const Vector6& start, double sigma, double gate,
              double radius_squared = std::numeric_limits<double>::infinity()) {
  Fit fit;
  fit.z = start;
  Eigen::VectorXd r, r_new, w, w_previous;
  Jacobian J, J_new;
  Linearise(model, fit.z, x1, x2, &r, &J);
  auto normal_matrix = [&](const Eigen::VectorXd& weights) {
    return Matrix6(Matrix6::Identity() + J.transpose() * weights.asDiagonal() * J / (sigma * sigma));
  };
  auto selected_cost = [&](const Vector6& z, const Eigen::VectorXd& residuals, const Eigen::VectorXd& weights) {
    return z.squaredNorm() + weights.dot(residuals.cwiseAbs2()) / (sigma * sigma);
  };
  fit.covariance = normal_matrix(Eigen::VectorXd::Ones(r.size())).ldlt().solve(Matrix6::Identity());
  // One Gauss-Newton step per selection: the set and the estimate settle together.
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Eigen::VectorXd scales = ResidualSigmas(J, fit.covariance, sigma);
    w = (r.array().abs() <= gate * scales.array()).cast<double>().matrix();
    const Matrix6 H = normal_matrix(w);
    const Eigen::LDLT<Matrix6> H_ldlt(H);
    Vector6 dz = -H_ldlt.solve(fit.z + J.transpose() * w.cwiseProduct(r) / (sigma * sigma));
    const double cost = selected_cost(fit.z, r, w);
    bool improved = false;
    Vector6 z_new;
    for (int halving = 0; halving < 20 && !improved; ++halving, dz /= 2) {
      z_new = fit.z + dz;
      if (z_new.squaredNorm() > radius_squared) continue;
      Linearise(model, z_new, x1, x2, &r_new, &J_new);
      improved = selected_cost(z_new, r_new, w) <= cost;
    }
    if (!improved) break;
    ++fit.iterations;
    fit.z = z_new;
    r.swap(r_new);
    J.swap(J_new);
    fit.covariance = H_ldlt.solve(Matrix6::Identity());
    const bool same_set = w_previous.size() == w.size() && w_previous == w;
    w_previous = w;
    if (same_set && dz.dot(H * dz) < 1e-4) break;
  }
  fit.cost = TruncatedCost(fit.z, r, sigma, gate);
  fit.inliers = static_cast<int>((r.array().abs() <= gate * sigma).count());
  return fit;
}

// Samples needed for 99 % confidence that one of them holds only right matches, when `inliers`
// of `n` matches are right.
int RequiredSamples(int inliers, int n) {
  const double share = n > 0 ? static_cast<double>(inliers) / n : 0;
  const double all_right = std::pow(share, kSampleSize);
  if (all_right >= 1) return 1;
  if (all_right <= 0) return kMaxSamples;
  return static_cast<int>(std::ceil(std::log(0.01) / std::log1p(-all_right)));
}

// Iteratively reweighted Gauss-Newton with graduated scales from the prior: every residual's
// Cauchy scale is its predicted sigma under the current uncertainty of the estimate (the prior's
// at first, so the odometry's own error does not count as an outlier); as the posterior shrinks,
// the scales shrink towards the location noise alone and the wrong matches lose their weight.
// The start of Consensus (a Cauchy fit alone can be captured by a group of wrong matches that a
// weakly observed direction of the pose lets it fit: docs/matching.md).
Vector6 CauchyStart(const PoseModel& model, const std::vector<Eigen::Vector2d>& x1,
                    const std::vector<Eigen::Vector2d>& x2, double sigma, int* steps) {
  Vector6 z = Vector6::Zero();
  Matrix6 covariance = Matrix6::Identity();
  Vector6 z_new;
  Eigen::VectorXd r, r_new;
  Jacobian J, J_new;
  Linearise(model, z, x1, x2, &r, &J);
  Eigen::VectorXd scales = ResidualSigmas(J, covariance, sigma);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    // The Gauss-Newton system of the robust objective at fixed scales (IRLS weights w).
    const Eigen::VectorXd c = kCauchyConstant * scales;
    const Eigen::VectorXd w = (1.0 + (r.array() / c.array()).square()).inverse().matrix();
    const Matrix6 H = Matrix6::Identity() + J.transpose() * w.asDiagonal() * J / (sigma * sigma);
    const Eigen::LDLT<Matrix6> H_ldlt(H);
    const Vector6 g = z + J.transpose() * (w.array() * r.array()).matrix() / (sigma * sigma);
    Vector6 dz = -H_ldlt.solve(g);
    // Backtracking: the objective is not quadratic (Sampson distances, Cauchy loss).
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
    ++*steps;
    covariance = H_ldlt.solve(Matrix6::Identity());
    const Eigen::VectorXd new_scales = ResidualSigmas(J, covariance, sigma);
    const double scale_change = ((new_scales - scales).array() / scales.array()).abs().maxCoeff();
    scales = new_scales;
    // Converged when the step is below a hundredth of the posterior's standard deviation along it
    // (dz^T H dz, the squared Newton decrement) and no residual's scale moved by 1 %.
    if (dz.dot(H * dz) < 1e-4 && scale_change < 1e-2) break;
  }
  return z;
}

}  // namespace

double SampsonDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2) {
  const Eigen::Vector3d line2 = F * x1.homogeneous();
  const Eigen::Vector3d line1 = F.transpose() * x2.homogeneous();
  const double norm_squared = line2.head<2>().squaredNorm() + line1.head<2>().squaredNorm();
  if (!(norm_squared > 0)) return 0;
  return x2.homogeneous().dot(line2) / std::sqrt(norm_squared);
}

double ChiSquare99(int degrees_of_freedom) {
  // The prior consistency gate at the same level as the 99 % gate of each match.
  constexpr double kQuantiles[6] = {6.635, 9.210, 11.345, 13.277, 15.086, 16.812};
  CHECK(degrees_of_freedom >= 1 && degrees_of_freedom <= 6) << degrees_of_freedom;
  return kQuantiles[degrees_of_freedom - 1];
}

double PriorDistanceSquared(const PairGeometry& prior, const Pose3& pose, int* rank) {
  const Eigen::SelfAdjointEigenSolver<Matrix6> solver(prior.covariance);
  const double largest = solver.eigenvalues().maxCoeff();
  Vector6 xi;
  xi.head<3>() = LogRotation(pose.RotationMatrix() * prior.camera2_T_camera1.RotationMatrix().transpose());
  xi.tail<3>() = pose.translation - prior.camera2_T_camera1.translation;
  double distance_squared = 0;
  int kept = 0;
  for (int k = 0; k < 6; ++k) {
    const double variance = solver.eigenvalues()(k);
    if (!(largest > 0 && variance > 1e-12 * largest)) continue;
    ++kept;
    const double projection = solver.eigenvectors().col(k).dot(xi);
    distance_squared += projection * projection / variance;
  }
  if (rank != nullptr) *rank = kept;
  return distance_squared;
}

PairRefinement RefinePairGeometry(const PairGeometry& prior, const std::vector<Eigen::Vector2d>& x1,
                                  const std::vector<Eigen::Vector2d>& x2, const PairRefinementSettings& settings) {
  CHECK_EQ(x1.size(), x2.size());
  CHECK(settings.location_sigma_px > 0 && settings.gate_sigmas > 0 && settings.min_inliers >= 0);
  PairRefinement result;
  result.prior = prior;
  result.geometry = prior;
  result.estimate = prior.camera2_T_camera1;
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

  // 1. The graduated Cauchy fit from the prior (a start: it follows most of the matches).
  int iterations = 0;
  Fit best = Consensus(model, x1, x2, CauchyStart(model, x1, x2, sigma, &iterations), sigma, settings.gate_sigmas);
  iterations += best.iterations;
  // 2. Hypotheses from random samples of kSampleSize matches with the prior, each scored by the
  //    truncated posterior and, when it beats the best score so far, refined by Consensus
  //    (LO-RANSAC, Chum et al. 2003). The number of samples is the usual adaptive one for 99 %
  //    confidence of drawing one sample of right matches, at the inlier share of the best fit.
  std::mt19937 rng(kSamplingSeed);
  const int n = result.matches;
  std::vector<int> order(static_cast<size_t>(n));
  std::vector<Eigen::Vector2d> sample1(kSampleSize), sample2(kSampleSize);
  double best_sample_cost = std::numeric_limits<double>::infinity();
  Eigen::VectorXd r;
  // Only when the local fit fails a test of step 3 below (outside the prior's ellipsoid, or too
  // few inliers): a fit that passes is accepted as it is (most pairs; this bounds the cost).
  const double prior_gate = ChiSquare99(m);
  const bool search = best.z.squaredNorm() > prior_gate || best.inliers < settings.min_inliers;
  for (int h = 0; search && h < RequiredSamples(best.inliers, n) && h < kMaxSamples; ++h) {
    std::iota(order.begin(), order.end(), 0);
    for (int k = 0; k < kSampleSize; ++k) {
      std::swap(order[static_cast<size_t>(k)],
                order[static_cast<size_t>(k + static_cast<int>(rng() % static_cast<unsigned>(n - k)))]);
      sample1[static_cast<size_t>(k)] = x1[static_cast<size_t>(order[static_cast<size_t>(k)])];
      sample2[static_cast<size_t>(k)] = x2[static_cast<size_t>(order[static_cast<size_t>(k)])];
    }
    const Vector6 z = GaussNewton(model, sample1, sample2, Vector6::Zero(), sigma, kSampleIterations, &iterations);
    Residuals(model, z, x1, x2, &r);
    const double cost = TruncatedCost(z, r, sigma, settings.gate_sigmas);
    if (!(cost < best_sample_cost)) continue;
    best_sample_cost = cost;
    const Fit fit = Consensus(model, x1, x2, z, sigma, settings.gate_sigmas);
    iterations += fit.iterations;
    if (fit.cost < best.cost) best = fit;
  }
  // 3. When the lowest truncated objective lies beyond the prior's 99 % ellipsoid, the maximum a
  //    posteriori pose among the poses the prior admits: the same search (starts from the prior,
  //    from the Cauchy fit and from samples, each pulled into the ellipsoid along the ray from the
  //    prior), with Consensus kept inside it. A group of wrong matches that agree with a pose
  //    beyond the gate can then no longer carry the estimate there; the right matches, which
  //    agree with a pose inside (the odometry's covariance covers its error), still can. The
  //    result must pass the same tests below, so a pair whose matches fit nothing inside the
  //    ellipsoid still falls back.
  if (best.z.squaredNorm() > prior_gate) {
    const auto into_ellipsoid = [&](const Vector6& start) -> Vector6 {
      const double norm_squared = start.squaredNorm();
      // A start on the surface would leave no room for the first step, so just inside it (0.99 of
      // the radius; any factor below 1 serves, the start only seeds Consensus).
      return norm_squared > prior_gate ? Vector6(start * (0.99 * std::sqrt(prior_gate / norm_squared))) : start;
    };
    Fit constrained = Consensus(model, x1, x2, Vector6::Zero(), sigma, settings.gate_sigmas, prior_gate);
    iterations += constrained.iterations;
    const Fit from_cauchy =
        Consensus(model, x1, x2, into_ellipsoid(best.z), sigma, settings.gate_sigmas, prior_gate);
    iterations += from_cauchy.iterations;
    if (from_cauchy.cost < constrained.cost) constrained = from_cauchy;
    std::mt19937 constrained_rng(kSamplingSeed);
    double best_constrained_sample = std::numeric_limits<double>::infinity();
    for (int h = 0; h < RequiredSamples(constrained.inliers, n) && h < kMaxSamples; ++h) {
      std::iota(order.begin(), order.end(), 0);
      for (int k = 0; k < kSampleSize; ++k) {
        std::swap(order[static_cast<size_t>(k)],
                  order[static_cast<size_t>(
                      k + static_cast<int>(constrained_rng() % static_cast<unsigned>(n - k)))]);
        sample1[static_cast<size_t>(k)] = x1[static_cast<size_t>(order[static_cast<size_t>(k)])];
        sample2[static_cast<size_t>(k)] = x2[static_cast<size_t>(order[static_cast<size_t>(k)])];
      }
      const Vector6 z = into_ellipsoid(
          GaussNewton(model, sample1, sample2, Vector6::Zero(), sigma, kSampleIterations, &iterations));
      Residuals(model, z, x1, x2, &r);
      const double cost = TruncatedCost(z, r, sigma, settings.gate_sigmas);
      if (!(cost < best_constrained_sample)) continue;
      best_constrained_sample = cost;
      const Fit fit = Consensus(model, x1, x2, z, sigma, settings.gate_sigmas, prior_gate);
      iterations += fit.iterations;
      if (fit.cost < constrained.cost) constrained = fit;
    }
    // Only a minimum of the objective itself counts: one held at the ellipsoid's surface by the
    // constraint is where the matches would pull the pose further out (they disagree with the
    // odometry, and the fall-back is the safe choice). So Consensus goes on from it without the
    // constraint; the tests below then reject an estimate that leaves the ellipsoid.
    best = Consensus(model, x1, x2, constrained.z, sigma, settings.gate_sigmas);
    iterations += best.iterations;
    result.constrained = true;
  }
  const Vector6& z = best.z;
  Matrix6 covariance = best.covariance;
  result.iterations = iterations;
  Jacobian J;
  Linearise(model, z, x1, x2, &r, &J);
  const Eigen::VectorXd scales = ResidualSigmas(J, covariance, sigma);

  result.inlier.resize(x1.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    result.inlier[static_cast<size_t>(i)] = std::abs(r(i)) <= settings.gate_sigmas * scales(i);
    result.inliers += result.inlier[static_cast<size_t>(i)] ? 1 : 0;
  }
  result.prior_distance_squared = z.squaredNorm();
  result.estimate = model.PoseAt(z);
  result.prior_gate = prior_gate;
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

#include "backend/bundle_adjustment/pose_covariance.h"

#include <ceres/cost_function.h>
#include <ceres/manifold.h>
#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <memory>

#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"
#include "backend/bundle_adjustment/pose_parameters.h"

namespace sfm {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// ceres::EigenQuaternionManifold's tangent delta multiplies the quaternion by (delta sin|delta| /
// |delta|, cos|delta|): a rotation by the angle 2 |delta|. PoseCovariance is in rotation vectors
// (R -> exp([w]x) R, w = 2 delta), so a Jacobian by delta is halved to one by w.
constexpr double kRotationPerTangent = 0.5;

// The normal equations J^T J of the whitened residuals, poses (frames 1..N-1, 6 each: rotation
// tangent, translation) by landmarks, accumulated block by block; the landmarks are eliminated one
// at a time (Schur complement, Triggs et al. 2000, section 6.1), leaving the reduced camera system.
class ReducedCameraSystem {
 public:
  explicit ReducedCameraSystem(int frames) : S_(Eigen::MatrixXd::Zero(6 * frames, 6 * frames)) {}

  // Adds a residual block's whitened Jacobians: `pose_jacobians[k]` (r x 6) for frame pose_frames[k].
  void AddPoses(const std::vector<int>& pose_frames, const std::vector<RowMajor>& pose_jacobians) {
    for (size_t a = 0; a < pose_frames.size(); ++a) {
      for (size_t b = 0; b < pose_frames.size(); ++b) {
        S_.block<6, 6>(6 * pose_frames[a], 6 * pose_frames[b]) +=
            pose_jacobians[a].transpose() * pose_jacobians[b];
      }
    }
  }

  // One landmark's blocks: its information H_ll (d x d), and per frame H_lc (d x 6) and the poses'
  // own H_cc (6 x 6). The landmark is marginalised: S -= H_cl H_ll^-1 H_lc.
  struct Landmark {
    Eigen::MatrixXd H_ll;
    std::map<int, Eigen::MatrixXd> H_lc;
    std::map<int, Matrix6> H_cc;
  };
  void Eliminate(const Landmark& landmark) {
    for (const auto& [frame, block] : landmark.H_cc) S_.block<6, 6>(6 * frame, 6 * frame) += block;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(landmark.H_ll);
    const Eigen::VectorXd values = eigen.eigenvalues();
    // A landmark its views do not fix (a line in an epipolar plane) carries no pose information
    // in the directions it leaves free: its pose terms are dropped with it (conservative).
    if (!(values.minCoeff() > 1e-9 * values.maxCoeff())) {
      for (const auto& [frame, block] : landmark.H_cc) S_.block<6, 6>(6 * frame, 6 * frame) -= block;
      ++dropped_;
      return;
    }
    const Eigen::MatrixXd inverse =
        eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
    std::vector<std::pair<int, Eigen::MatrixXd>> Y;  // H_ll^-1 H_lc per frame
    for (const auto& [frame, block] : landmark.H_lc) Y.emplace_back(frame, inverse * block);
    for (const auto& [f, H_lf] : landmark.H_lc) {
      for (const auto& [g, Y_g] : Y) S_.block<6, 6>(6 * f, 6 * g) -= H_lf.transpose() * Y_g;
    }
  }

  const Eigen::MatrixXd& S() const { return S_; }
  int dropped() const { return dropped_; }

 private:
  Eigen::MatrixXd S_;
  int dropped_ = 0;
};

// Evaluates `cost` at `parameters` and returns the Jacobians in the tangent spaces (the quaternion
// and line manifolds applied), each divided by `sigma`. false when the cost cannot be evaluated.
bool TangentJacobians(const ceres::CostFunction& cost, const std::vector<double*>& parameters,
                      const std::vector<const ceres::Manifold*>& manifolds, double sigma,
                      std::vector<RowMajor>* tangent) {
  const int residuals = cost.num_residuals();
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  std::vector<RowMajor> ambient;
  std::vector<double*> ambient_pointers;
  for (int32_t size : sizes) ambient.emplace_back(residuals, size);
  for (RowMajor& block : ambient) ambient_pointers.push_back(block.data());
  Eigen::VectorXd r(residuals);
  if (!cost.Evaluate(parameters.data(), r.data(), ambient_pointers.data())) return false;
  tangent->clear();
  for (size_t k = 0; k < sizes.size(); ++k) {
    if (manifolds[k] == nullptr) {
      tangent->push_back(ambient[k] / sigma);
      continue;
    }
    RowMajor plus(manifolds[k]->AmbientSize(), manifolds[k]->TangentSize());
    if (!manifolds[k]->PlusJacobian(parameters[k], plus.data())) return false;
    tangent->push_back(ambient[k] * plus / sigma);
  }
  return true;
}

}  // namespace

Status ComputePoseCovariance(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                             const std::vector<Pose3>& world_T_base_refined, const Landmarks& landmarks,
                             const BundleAdjustmentOptions& options, double pixel_sigma_px,
                             PoseCovariance* covariance) {
  const int n = static_cast<int>(world_T_base_refined.size());
  if (static_cast<int>(world_T_base_odometry.size()) != n)
    return Status::Error("pose covariance: sizes differ");
  if (!(pixel_sigma_px > 0)) return Status::Error("pose covariance: pixel sigma must be > 0");
  const OdometryNoise& noise = calibration.odometry_noise;
  if (!(noise.rotation_sigma > 0 && noise.translation_sigma > 0)) {
    return Status::Error("pose covariance: odometry sigmas must be > 0");
  }
  const CameraModel camera(calibration.base_T_camera, calibration.camera.fx, calibration.camera.fy,
                           calibration.camera.cx, calibration.camera.cy);
  std::vector<PoseParameters> poses;
  for (const Pose3& pose : world_T_base_refined) poses.push_back(PoseParameters::FromPose(pose));
  const ceres::EigenQuaternionManifold quaternion;
  const OrthonormalLineManifold line_manifold;
  ReducedCameraSystem system(n);

  // Frame 0 is the gauge: its pose is fixed, its columns are not part of the system.
  auto pose_blocks = [&](int frame, const std::vector<RowMajor>& tangent, int first_block,
                         std::vector<int>* frames, std::vector<RowMajor>* jacobians) {
    if (frame == 0) return;
    RowMajor J(tangent[first_block].rows(), 6);
    J << kRotationPerTangent * tangent[first_block], tangent[first_block + 1];
    frames->push_back(frame);
    jacobians->push_back(J);
  };

  // One image landmark: its residual blocks' Jacobians into H_ll, H_lc, H_cc.
  auto add_landmark = [&](double* parameters, int size, const ceres::Manifold* manifold, auto observations,
                          auto make_cost) -> Status {
    ReducedCameraSystem::Landmark landmark;
    const int tangent_size = manifold ? manifold->TangentSize() : size;
    landmark.H_ll = Eigen::MatrixXd::Zero(tangent_size, tangent_size);
    for (const auto& observation : observations) {
      if (observation.frame < 0 || observation.frame >= n) return Status::Error("pose covariance: bad frame");
      PoseParameters& pose = poses[observation.frame];
      const std::unique_ptr<ceres::CostFunction> cost(make_cost(observation));
      std::vector<RowMajor> tangent;
      if (!TangentJacobians(*cost, {pose.rotation.data(), pose.translation.data(), parameters},
                            {&quaternion, nullptr, manifold}, pixel_sigma_px, &tangent)) {
        continue;  // behind the camera on these poses: no information
      }
      landmark.H_ll += tangent[2].transpose() * tangent[2];
      if (observation.frame == 0) continue;
      RowMajor J(tangent[0].rows(), 6);
      J << kRotationPerTangent * tangent[0], tangent[1];
      landmark.H_lc[observation.frame] = tangent[2].transpose() * J;
      landmark.H_cc[observation.frame] = J.transpose() * J;
    }
    system.Eliminate(landmark);
    return Status::Ok();
  };

  for (const PointLandmark& point : landmarks.points) {
    Eigen::Vector3d position = point.position;
    SFM_RETURN_IF_ERROR(add_landmark(
        position.data(), 3, nullptr, point.observations,
        [&](const PointObservation& o) { return PointReprojectionCost::Create(camera, o.pixel); }));
  }
  for (const LineLandmark& line : landmarks.lines) {
    OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
    SFM_RETURN_IF_ERROR(add_landmark(
        parameters.data(), 6, &line_manifold, line.observations,
        [&](const LineObservation& o) { return LineReprojectionCost::Create(camera, o.p0, o.p1); }));
  }
  // The odometry priors, whitened by their noise model as in BundleAdjust.
  for (int f = 0; f + 1 < n; ++f) {
    const Pose3 motion = world_T_base_odometry[f].Inverse() * world_T_base_odometry[f + 1];
    const OdometryStepSigmas sigmas = OdometryStepSigmasFor(motion.translation.norm(), noise, options);
    const std::unique_ptr<ceres::CostFunction> cost(
        OdometryPriorCost::Create(motion, noise.rotation_sigma, sigmas.along_m, sigmas.across_m));
    std::vector<RowMajor> tangent;
    if (!TangentJacobians(*cost,
                          {poses[f].rotation.data(), poses[f].translation.data(),
                           poses[f + 1].rotation.data(), poses[f + 1].translation.data()},
                          {&quaternion, nullptr, &quaternion, nullptr}, 1.0, &tangent)) {
      return Status::Error("pose covariance: an odometry prior could not be evaluated");
    }
    std::vector<int> frames;
    std::vector<RowMajor> jacobians;
    pose_blocks(f, tangent, 0, &frames, &jacobians);
    pose_blocks(f + 1, tangent, 2, &frames, &jacobians);
    system.AddPoses(frames, jacobians);
  }

  covariance->camera_R_world.clear();
  covariance->centre.clear();
  covariance->lever.clear();
  for (const Pose3& world_T_base : world_T_base_refined) {
    const Pose3 world_T_camera = world_T_base * calibration.base_T_camera;
    covariance->camera_R_world.push_back(world_T_camera.RotationMatrix().transpose());
    covariance->centre.push_back(world_T_camera.translation);
    covariance->lever.push_back(world_T_base.RotationMatrix() * calibration.base_T_camera.translation);
  }
  covariance->tangent = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  if (n < 2) return Status::Ok();
  const int m = 6 * (n - 1);
  const Eigen::MatrixXd reduced = system.S().bottomRightCorner(m, m);
  const Eigen::LLT<Eigen::MatrixXd> llt(reduced);
  if (llt.info() != Eigen::Success)
    return Status::Error("pose covariance: the reduced camera system is singular");
  covariance->tangent.bottomRightCorner(m, m) = llt.solve(Eigen::MatrixXd::Identity(m, m));
  return Status::Ok();
}

std::vector<PoseCovarianceCheck> CheckPoseCovariance(const PoseCovariance& covariance,
                                                     const std::vector<Pose3>& world_T_camera_estimate,
                                                     const std::vector<Pose3>& world_T_camera_truth,
                                                     const std::vector<int>& lags) {
  CHECK_EQ(world_T_camera_estimate.size(), world_T_camera_truth.size());
  CHECK_EQ(static_cast<int>(world_T_camera_estimate.size()), covariance.frames());
  const int n = covariance.frames();
  std::vector<PoseCovarianceCheck> checks;
  for (int lag : lags) {
    PoseCovarianceCheck check;
    check.lag = lag;
    for (int f0 = 0; f0 + lag < n && lag > 0; ++f0) {
      const int i = f0 + lag;
      const Eigen::Matrix<double, 6, 6> relative = covariance.Relative(i, i, f0);
      check.predicted_rotation_rad += relative.topLeftCorner<3, 3>().trace();
      check.predicted_centre_m += relative.bottomRightCorner<3, 3>().trace();
      const Pose3 estimate = world_T_camera_estimate[f0].Inverse() * world_T_camera_estimate[i];
      const Pose3 truth = world_T_camera_truth[f0].Inverse() * world_T_camera_truth[i];
      const double angle = Eigen::AngleAxisd(truth.rotation.conjugate() * estimate.rotation).angle();
      check.actual_rotation_rad += angle * angle;
      check.actual_centre_m += (estimate.translation - truth.translation).squaredNorm();
      ++check.pairs;
    }
    if (check.pairs == 0) continue;
    for (double* value : {&check.predicted_rotation_rad, &check.actual_rotation_rad,
                          &check.predicted_centre_m, &check.actual_centre_m}) {
      *value = std::sqrt(*value / check.pairs);
    }
    checks.push_back(check);
  }
  return checks;
}

}  // namespace sfm

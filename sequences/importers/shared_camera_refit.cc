#include "sequences/importers/shared_camera_refit.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "geometry/alignment.h"
#include "sequences/importers/shared_camera_refit_costs.h"

namespace sfm {
namespace {

// Fewer observations than this leave a view's 6 pose dof barely determined (as for PnP).
constexpr int kMinObservationsPerView = 6;

using Pose6 = std::array<double, 6>;  // angle-axis of camera_R_world, then camera_t_world

Pose6 ToPose6(const Pose3& camera_T_world) {
  const Eigen::AngleAxisd angle_axis(camera_T_world.rotation);
  const Eigen::Vector3d w = angle_axis.angle() * angle_axis.axis();
  const Eigen::Vector3d& t = camera_T_world.translation;
  return {w.x(), w.y(), w.z(), t.x(), t.y(), t.z()};
}

Pose3 FromPose6(const Pose6& pose) {
  const Eigen::Vector3d w(pose[0], pose[1], pose[2]);
  const double angle = w.norm();
  const Eigen::Quaterniond q =
      angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle)) : Eigen::Quaterniond::Identity();
  return Pose3(q, Eigen::Vector3d(pose[3], pose[4], pose[5]));
}

Eigen::Vector3d Centre(const Pose3& camera_T_world) { return camera_T_world.Inverse().translation; }

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Per-view and overall median reprojection distance.
void ReprojectionMedians(const Eigen::Matrix3d& K, double k1, const std::vector<Pose3>& camera_T_world,
                         const std::vector<Eigen::Vector3d>& points,
                         const std::vector<RefitObservation>& observations, std::vector<double>* view_medians,
                         double* median) {
  std::vector<std::vector<double>> per_view(camera_T_world.size());
  std::vector<double> all;
  for (const RefitObservation& o : observations) {
    const double error =
        (ProjectWithRadial(K, k1, camera_T_world[o.view] * points[o.point]) - o.pixel).norm();
    per_view[o.view].push_back(error);
    all.push_back(error);
  }
  if (view_medians) {
    view_medians->clear();
    for (const std::vector<double>& errors : per_view) view_medians->push_back(Median(errors));
  }
  *median = Median(all);
}

}  // namespace

Eigen::Vector2d ProjectWithRadial(const Eigen::Matrix3d& K, double k1, const Eigen::Vector3d& point_camera) {
  const Eigen::Vector2d x = point_camera.hnormalized();
  const double radial = 1 + k1 * x.squaredNorm();
  return Eigen::Vector2d(K(0, 0) * x.x() * radial + K(0, 2), K(1, 1) * x.y() * radial + K(1, 2));
}

Status RefitSharedCamera(const Eigen::Matrix3d& start_K, const std::vector<Pose3>& start_camera_T_world,
                         const std::vector<Eigen::Vector3d>& start_points,
                         const std::vector<RefitObservation>& observations,
                         const std::vector<Eigen::Vector3d>& reference_centres,
                         const SharedCameraRefitOptions& options, SharedCameraRefit* result) {
  const size_t views = start_camera_T_world.size();
  if (views < 2)
    return Status::Error("shared camera refit: needs at least 2 views, found " + std::to_string(views));
  if (reference_centres.size() != views) {
    return Status::Error("shared camera refit: " + std::to_string(reference_centres.size()) +
                         " reference centres for " + std::to_string(views) + " views");
  }
  std::vector<int> per_view(views, 0);
  for (const RefitObservation& o : observations) {
    if (o.view < 0 || static_cast<size_t>(o.view) >= views || o.point < 0 ||
        static_cast<size_t>(o.point) >= start_points.size()) {
      return Status::Error("shared camera refit: observation of point " + std::to_string(o.point) +
                           " in view " + std::to_string(o.view) + " is out of range");
    }
    if ((start_camera_T_world[o.view] * start_points[o.point]).z() <= 0) {
      return Status::Error("shared camera refit: point " + std::to_string(o.point) + " lies behind camera " +
                           std::to_string(o.view) + " at the start");
    }
    ++per_view[o.view];
  }
  for (size_t v = 0; v < views; ++v) {
    if (per_view[v] < kMinObservationsPerView) {
      return Status::Error("shared camera refit: view " + std::to_string(v) + " has " +
                           std::to_string(per_view[v]) + " observations; at least " +
                           std::to_string(kMinObservationsPerView) + " are needed");
    }
  }
  const Eigen::Vector3d first_centre = Centre(start_camera_T_world.front());
  const double first_to_last = (Centre(start_camera_T_world.back()) - first_centre).norm();
  if (!(first_to_last > 0))
    return Status::Error("shared camera refit: the first and last camera centres coincide");

  SharedCameraRefit refit;
  ReprojectionMedians(start_K, options.k1, start_camera_T_world, start_points, observations, nullptr,
                      &refit.start_median_px);

  std::array<double, 4> intrinsics = {start_K(0, 0), start_K(1, 1), start_K(0, 2), start_K(1, 2)};
  double k1 = options.k1;
  std::vector<Pose6> poses;
  for (const Pose3& pose : start_camera_T_world) poses.push_back(ToPose6(pose));
  std::vector<Eigen::Vector3d> points = start_points;

  ceres::Problem problem;
  for (const RefitObservation& o : observations) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RefitReprojectionCost, 2, 4, 1, 6, 3>(
                                 new RefitReprojectionCost(o.pixel)),
                             new ceres::HuberLoss(options.huber_px), intrinsics.data(), &k1,
                             poses[o.view].data(), points[o.point].data());
  }
  if (!options.radial_k1) problem.SetParameterBlockConstant(&k1);
  if (!options.refine_focal && !options.refine_principal_point) {
    problem.SetParameterBlockConstant(intrinsics.data());
  } else if (!options.refine_focal || !options.refine_principal_point) {
    problem.SetManifold(
        intrinsics.data(),
        new ceres::SubsetManifold(4, options.refine_focal ? std::vector<int>{2, 3} : std::vector<int>{0, 1}));
  }
  problem.SetParameterBlockConstant(poses.front().data());
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RefitCentreDistanceCost, 1, 6>(
                               new RefitCentreDistanceCost(first_centre, first_to_last)),
                           nullptr, poses.back().data());

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-12;
  solver.gradient_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    return Status::Error("shared camera refit: the solver failed (" + summary.message + ")");
  }
  refit.iterations = static_cast<int>(summary.iterations.size());
  refit.observations = static_cast<int>(observations.size());

  // The gauge: the similarity that best maps the refit centres onto the reference.
  std::vector<Eigen::Vector3d> centres;
  for (const Pose6& pose : poses) centres.push_back(Centre(FromPose6(pose)));
  const Similarity3 reference_S_refit = AlignSim3(centres, reference_centres);
  refit.gauge_scale = reference_S_refit.scale;
  const Eigen::Quaterniond& rotation = reference_S_refit.rigid.rotation;
  for (size_t v = 0; v < views; ++v) {
    const Pose3 camera_T_world = FromPose6(poses[v]);
    // The rotation turns with the world; the centre maps as a point; t = -R C.
    const Eigen::Quaterniond R = camera_T_world.rotation * rotation.conjugate();
    const Eigen::Vector3d C = reference_S_refit * centres[v];
    refit.camera_T_world.emplace_back(R, -(R * C));
    refit.centre_offset.push_back((C - reference_centres[v]).norm());
  }
  for (const Eigen::Vector3d& X : points) refit.points.push_back(reference_S_refit * X);
  refit.K << intrinsics[0], 0, intrinsics[2], 0, intrinsics[1], intrinsics[3], 0, 0, 1;
  refit.k1 = k1;
  ReprojectionMedians(refit.K, refit.k1, refit.camera_T_world, refit.points, observations,
                      &refit.view_median_px, &refit.median_px);
  *result = std::move(refit);
  return Status::Ok();
}

}  // namespace sfm

#include "backend/bundle_adjustment/bundle_adjuster.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "backend/bundle_adjustment/problem_builder.h"

namespace sfm {
namespace {

bool Finite(const Eigen::Vector2d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

Status CheckInput(const Calibration& calibration, const std::vector<Pose3>& odometry,
                  const Landmarks& landmarks) {
  auto error = [](const std::string& what) { return Status::Error("bundle adjustment: " + what); };
  const Camera& camera = calibration.camera;
  if (!(camera.fx > 0 && camera.fy > 0 && std::isfinite(camera.cx) && std::isfinite(camera.cy))) {
    return error("the camera's fx and fy must be > 0, cx and cy finite");
  }
  const OdometryNoise& noise = calibration.odometry_noise;
  if (!(noise.translation_sigma > 0 && std::isfinite(noise.translation_sigma))) {
    return error("odometry translation_sigma must be > 0");
  }
  if (!(noise.rotation_sigma > 0 && std::isfinite(noise.rotation_sigma))) {
    return error("odometry rotation_sigma must be > 0 rad");
  }
  if (odometry.empty()) return error("no odometry pose");
  const int frames = static_cast<int>(odometry.size());
  for (int f = 0; f < frames; ++f) {
    if (!odometry[f].translation.allFinite() || !odometry[f].rotation.coeffs().allFinite() ||
        !(odometry[f].rotation.norm() > 0)) {
      return error("odometry pose " + std::to_string(f) + " is not a finite rigid transform");
    }
  }
  auto bad_frame = [frames](int frame) { return frame < 0 || frame >= frames; };
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    const PointLandmark& point = landmarks.points[i];
    if (!Finite(point.position)) return error("point " + std::to_string(i) + " is not finite");
    for (const PointObservation& observation : point.observations) {
      if (bad_frame(observation.frame) || !Finite(observation.pixel)) {
        return error("point " + std::to_string(i) + " has an observation of frame " +
                     std::to_string(observation.frame) + " (of " + std::to_string(frames) +
                     ") or a pixel that is not finite");
      }
    }
  }
  for (size_t i = 0; i < landmarks.lines.size(); ++i) {
    const LineLandmark& line = landmarks.lines[i];
    if (!Finite(line.point) || !Finite(line.direction) || !(line.direction.norm() > 0)) {
      return error("line " + std::to_string(i) + " needs a finite point and a non-zero direction");
    }
    if (line.point_landmark < -1 || line.point_landmark >= static_cast<int>(landmarks.points.size())) {
      return error("line " + std::to_string(i) + " refers to point " + std::to_string(line.point_landmark));
    }
    for (const LineObservation& observation : line.observations) {
      if (bad_frame(observation.frame) || !Finite(observation.p0) || !Finite(observation.p1)) {
        return error("line " + std::to_string(i) + " has an observation of frame " +
                     std::to_string(observation.frame) + " (of " + std::to_string(frames) +
                     ") or an end-point that is not finite");
      }
    }
  }
  return Status::Ok();
}

bool FiniteRigid(const Pose3& pose) {
  return pose.translation.allFinite() && pose.rotation.coeffs().allFinite() && pose.rotation.norm() > 0;
}

// Solves after the last joint solve that drop the landmarks it made unobservable, at most
// (docs/bundle_adjustment.md, "Robust loss, stages and outliers", step 7).
constexpr int kObservabilityRounds = 3;

}  // namespace

BundleAdjustment::BundleAdjustment(const std::vector<Pose3>& world_T_base_odometry,
                                   double odometry_scale_start, const BundleAdjustmentOptions& options,
                                   Reconstruction* reconstruction, BundleAdjustmentSummary* summary)
    : start_time_(std::chrono::steady_clock::now()),
      odometry_scale_start_(odometry_scale_start),
      reconstruction_(CHECK_NOTNULL(reconstruction)),
      landmarks_(&reconstruction->landmarks),
      summary_(CHECK_NOTNULL(summary)),
      setup_(reconstruction->calibration, world_T_base_odometry, options),
      floor_(setup_),
      filter_(setup_, parameters_, landmarks_, summary_) {
  *summary_ = BundleAdjustmentSummary();
}

Status BundleAdjustment::CheckStart() const {
  SFM_RETURN_IF_ERROR(setup_.options.Check());
  SFM_RETURN_IF_ERROR(CheckInput(reconstruction_->calibration, setup_.odometry, *landmarks_));
  const std::vector<Pose3>& start = reconstruction_->world_T_base;
  if (start.size() != setup_.odometry.size()) {
    return Status::Error("bundle adjustment: " + std::to_string(start.size()) + " start poses for " +
                         std::to_string(setup_.odometry.size()) + " odometry poses");
  }
  for (size_t f = 0; f < start.size(); ++f) {
    if (!FiniteRigid(start[f])) {
      return Status::Error("bundle adjustment: start pose " + std::to_string(f) +
                           " is not a finite rigid transform");
    }
  }
  // The first pose is the gauge (SPEC section 3): it stays the odometry's.
  const Pose3& first = setup_.odometry[0];
  if (!((start[0].translation - first.translation).norm() <= 1e-9 * (1 + first.translation.norm()) &&
        start[0].rotation.angularDistance(first.rotation) <= 1e-9)) {
    return Status::Error(
        "bundle adjustment: the first start pose must be the first odometry pose (the gauge)");
  }
  if (!(odometry_scale_start_ > 0 && std::isfinite(odometry_scale_start_))) {
    return Status::Error("bundle adjustment: the start odometry scale must be finite and > 0");
  }
  return Status::Ok();
}

Status BundleAdjustment::Start() {
  SFM_RETURN_IF_ERROR(CheckStart());
  for (const Pose3& pose : reconstruction_->world_T_base) {
    parameters_.poses.push_back(PoseParameters::FromPose(pose));
  }
  parameters_.odometry_scale = odometry_scale_start_;
  parameters_.with_bias = EstimatesRotationBias(setup_.options, setup_.base_T_camera, setup_.odometry);
  summary_->frames = static_cast<int>(parameters_.poses.size());
  filter_.DropUnusableObservations();
  filter_.RemoveLandmarksWithFewViews();
  filter_.DropUnobservableLandmarks(/*refined=*/false);
  summary_->points = static_cast<int>(landmarks_->points.size());
  summary_->lines = static_cast<int>(landmarks_->lines.size());
  summary_->observations = filter_.CountObservations();
  state_ = State::kRunning;
  if (parameters_.poses.size() < 2 || summary_->observations == 0) {
    summary_->solver_report = "nothing to solve: no observable landmark in two frames";
    state_ = State::kNothingToSolve;
  }
  return Status::Ok();
}

// 1. Poses and points at the coarse loss scale: from the odometry, errors of tens of pixels are
//    drift, not outliers. Lines are left out: triangulated on drifting poses they start far worse
//    than points (degrees, decimetres) and trap a joint solve in wrong minima.
// 2. Each line alone on those poses (with no point, on the odometry's; then a coarse joint solve
//    refines the poses with the lines before step 3 judges anything by its error).
// 3. Observations beyond the coarse scale go (that loss already treated them as outliers), and
//    landmarks that the refined poses show unobservable (the odometry's drift can hide a line
//    parallel to the motion; a near-degenerate landmark makes the joint system singular).
// 4. The floor prior, decided on the coarse map (its floor is where the odometry's scale put it).
Status BundleAdjustment::SolveCoarse() {
  if (finished()) return Status::Ok();
  const BundleAdjustmentOptions& options = setup_.options;
  const double coarse_scale_px = std::max(options.coarse_loss_scale_px, options.robust_loss_scale_px);
  if (!landmarks_->points.empty()) {
    SFM_RETURN_IF_ERROR(Solve(coarse_scale_px, /*with_lines=*/false, options.function_tolerance));
  }
  RefineLinesOnFixedPoses(setup_, coarse_scale_px, &parameters_.poses, landmarks_);
  if (landmarks_->points.empty()) {
    SFM_RETURN_IF_ERROR(Solve(coarse_scale_px, /*with_lines=*/true, options.function_tolerance));
  }
  filter_.RemoveOutliers(std::max(coarse_scale_px, options.outlier_threshold_px));
  filter_.RemoveLandmarksWithFewViews();
  filter_.DropUnobservableLandmarks(/*refined=*/true);
  if (filter_.CountObservations() == 0) {
    RevertToOdometry("no landmark left observable on the refined poses");
  } else {
    floor_.Select(/*first=*/true, parameters_, *landmarks_, summary_);
    const double gain = floor_.StartGain(parameters_);
    if (gain != 1) {
      ScaleMapAboutFirstCamera(gain);
      floor_.NoteStartScale(parameters_.odometry_scale, summary_);
    }
  }
  WritePoses();
  return Status::Ok();
}

// 5. Everything at the fine loss scale. A solve that an outlier round follows stops at the looser
//    intermediate tolerance; the returned result always comes from a solve at function_tolerance.
Status BundleAdjustment::SolveFine() {
  if (finished()) return Status::Ok();
  const BundleAdjustmentOptions& options = setup_.options;
  loose_ = options.outlier_rounds > 0;
  SFM_RETURN_IF_ERROR(Solve(options.robust_loss_scale_px, /*with_lines=*/true,
                            loose_ ? options.intermediate_function_tolerance : options.function_tolerance));
  WritePoses();
  return Status::Ok();
}

Status BundleAdjustment::AcceptChangedMap() {
  if (finished()) return Status::Ok();
  const BundleAdjustmentOptions& options = setup_.options;
  filter_.DropUnusableObservations();
  filter_.RemoveLandmarksWithFewViews();
  filter_.DropUnobservableLandmarks(/*refined=*/true);
  if (filter_.CountObservations() == 0) {
    RevertToOdometry("no landmark left after the map's change");
    WritePoses();
    return Status::Ok();
  }
  floor_.Select(/*first=*/false, parameters_, *landmarks_, summary_);
  if (options.outlier_rounds == 0) {
    SFM_RETURN_IF_ERROR(Solve(options.robust_loss_scale_px, /*with_lines=*/true, options.function_tolerance));
  }
  WritePoses();
  return Status::Ok();
}

// 6. The outlier rounds. 7. The last solve's own landmarks under the rules every earlier solve's
//    passed: a landmark it made unobservable (on Strecha, lines slid behind or through a camera,
//    which their images cannot show, and still holding the poses) is dropped, and the rest solved
//    again. 8. The floor scale's line search.
Status BundleAdjustment::Filter() {
  if (finished()) return Status::Ok();
  const BundleAdjustmentOptions& options = setup_.options;
  for (int round = 0; round < options.outlier_rounds; ++round) {
    const int outliers = filter_.RemoveOutliers(options.outlier_threshold_px);
    filter_.RemoveLandmarksWithFewViews();
    const int unobservable = filter_.DropUnobservableLandmarks(/*refined=*/true);
    if (outliers + unobservable == 0) break;
    if (filter_.CountObservations() == 0) {
      RevertToOdometry("every landmark was removed after solving");
      WritePoses();
      return Status::Ok();
    }
    // The removals renumbered the landmarks: the floor's are selected again.
    floor_.Select(/*first=*/false, parameters_, *landmarks_, summary_);
    loose_ = round + 1 < options.outlier_rounds;
    SFM_RETURN_IF_ERROR(Solve(options.robust_loss_scale_px, /*with_lines=*/true,
                              loose_ ? options.intermediate_function_tolerance : options.function_tolerance));
  }
  if (loose_) {
    SFM_RETURN_IF_ERROR(Solve(options.robust_loss_scale_px, /*with_lines=*/true, options.function_tolerance));
  }
  for (int round = 0; round < kObservabilityRounds; ++round) {
    const int unobservable = filter_.DropUnobservableLandmarks(/*refined=*/true);
    filter_.RemoveLandmarksWithFewViews();
    if (unobservable == 0) break;
    summary_->landmarks_unobservable_after_last_solve += unobservable;
    ++summary_->observability_solves;
    if (filter_.CountObservations() == 0) {
      RevertToOdometry("every landmark was removed after solving");
      WritePoses();
      return Status::Ok();
    }
    floor_.Select(/*first=*/false, parameters_, *landmarks_, summary_);
    SFM_RETURN_IF_ERROR(Solve(options.robust_loss_scale_px, /*with_lines=*/true, options.function_tolerance));
  }
  SFM_RETURN_IF_ERROR(SearchScale());
  WritePoses();
  return Status::Ok();
}

void BundleAdjustment::Finish() {
  if (state_ == State::kRunning) {
    filter_.ComputeRms();
    FinishFloorSummary();
  }
  summary_->odometry_rotation_bias_estimated = parameters_.with_bias;
  if (summary_->odometry_rotation_bias_estimated) {
    const std::array<double, 3>& b = summary_->odometry_rotation_bias_rad;
    LOG(INFO) << "bundle adjustment: odometry rotation bias per step (" << b[0] << ", " << b[1] << ", "
              << b[2] << ") rad, angle-axis in the base frame";
  }
  if (!parameters_.poses.empty()) WritePoses();
  summary_->time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time_).count();
}

namespace {

// Hands each iteration of a solve to the BundleAdjustment's IterationHook; changes nothing.
class IterationHookCallback : public ceres::IterationCallback {
 public:
  IterationHookCallback(const BundleAdjustment::IterationHook& hook, int solve)
      : hook_(hook), solve_(solve) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    hook_(solve_, summary.iteration);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const BundleAdjustment::IterationHook& hook_;
  const int solve_;
};

}  // namespace

Status BundleAdjustment::Solve(double loss_scale_px, bool with_lines, double function_tolerance) {
  JointProblem problem(setup_, floor_, loss_scale_px, with_lines, &parameters_, *landmarks_);
  ceres::Solver::Summary ceres_summary;
  IterationHookCallback callback(iteration_hook_, summary_->solves + 1);
  problem.Solve(function_tolerance, &ceres_summary, iteration_hook_ ? &callback : nullptr);
  if (!ceres_summary.IsSolutionUsable()) {
    return Status::Error("bundle adjustment: Ceres failed: " + ceres_summary.message);
  }
  const std::vector<int>& apart_lines = problem.apart_lines();
  const int iterations = ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
  // Where a solve's time goes (docs/bundle_adjustment.md, "Solver").
  VLOG(1) << "bundle adjustment solve: loss " << loss_scale_px << " px, " << (with_lines ? "lines, " : "")
          << (apart_lines.empty() ? "" : std::to_string(apart_lines.size()) + " two-view lines apart, ")
          << (parameters_.hold_scale ? "scale held, " : "")
          << ceres::LinearSolverTypeToString(ceres_summary.linear_solver_type_used) << ", tolerance "
          << function_tolerance << ": " << iterations << " iterations, cost " << ceres_summary.initial_cost
          << " -> " << ceres_summary.final_cost << "; " << ceres_summary.total_time_in_seconds
          << " s (preprocessor " << ceres_summary.preprocessor_time_in_seconds << ", residuals "
          << ceres_summary.residual_evaluation_time_in_seconds << ", jacobians "
          << ceres_summary.jacobian_evaluation_time_in_seconds << ", linear solver "
          << ceres_summary.linear_solver_time_in_seconds << ", inner iterations "
          << ceres_summary.inner_iteration_time_in_seconds << ")";
  if (summary_->solves == 0) {
    summary_->initial_cost = ceres_summary.initial_cost;
    summary_->converged = true;
  }
  ++summary_->solves;
  summary_->iterations += iterations;
  summary_->final_cost = ceres_summary.final_cost;
  summary_->converged = summary_->converged && ceres_summary.termination_type == ceres::CONVERGENCE;
  summary_->solver_report = ceres_summary.BriefReport();
  problem.WriteLandmarks(landmarks_);
  // The two-view lines on the solve's poses: their least cost there (about 0) completes the
  // solve's cost, which the scale line search compares.
  if (!apart_lines.empty()) {
    summary_->final_cost +=
        RefineLinesOnFixedPoses(setup_, loss_scale_px, &parameters_.poses, landmarks_, &apart_lines);
  }
  return Status::Ok();
}

void BundleAdjustment::RevertToOdometry(const std::string& why) {
  for (size_t f = 0; f < parameters_.poses.size(); ++f) {
    parameters_.poses[f] = PoseParameters::FromPose(setup_.odometry[f]);
  }
  parameters_.odometry_scale = 1;
  parameters_.rotation_bias = {0, 0, 0};
  floor_.Clear();
  FinishFloorSummary();
  summary_->solver_report = why + "; the trajectory is the odometry's";
  state_ = State::kReverted;
}

// The map scaled by `gain` about the first camera's centre (its pose is held): the cameras'
// centres (rotations kept), every landmark, the floor lines' anchors and the odometry's scale
// factor. The images see no change (cameras at the first camera's height keep it); only the
// floor's height and the scale prior do.
void BundleAdjustment::ScaleMapAboutFirstCamera(double gain) {
  std::vector<PoseParameters>& poses = parameters_.poses;
  const Pose3& base_T_camera = setup_.base_T_camera;
  const Eigen::Vector3d centre = (poses[0].ToPose() * base_T_camera).translation;
  for (size_t f = 1; f < poses.size(); ++f) {
    Pose3 camera = poses[f].ToPose() * base_T_camera;
    camera.translation = centre + gain * (camera.translation - centre);
    poses[f] = PoseParameters::FromPose(camera * base_T_camera.Inverse());
  }
  ScaleLandmarksAbout(centre, gain, landmarks_);
  floor_.ScaleAnchorsAbout(centre, gain);
  parameters_.odometry_scale *= gain;
}

// The line search on the odometry's scale factor after the last joint solve
// (docs/bundle_adjustment.md, "Floor scale bias: the start and the line search"). The joint solves
// stop, by their function tolerance, with the scale part-way along its shallow direction; with
// lambda held, the same solves converge. So: the map scaled to lambda (1 - d) and lambda (1 + d),
// each solved with lambda held (at the intermediate tolerance), a parabola through their costs
// and the last solve's at lambda, and the map solved once more (at function_tolerance) at its
// minimum, at most 2 d away (where the three samples still describe the cost). d is lambda's
// standard error through the per-step priors, translation_sigma / sqrt(steps): the change of
// scale the odometry itself cannot tell. The result is kept only if its cost is below the last
// solve's.
Status BundleAdjustment::SearchScale() {
  if (!floor_.applied() || !floor_.holds_landmarks() || parameters_.poses.size() < 2) return Status::Ok();
  const BundleAdjustmentOptions& options = setup_.options;
  const std::vector<PoseParameters> poses = parameters_.poses;
  const Landmarks landmarks = *landmarks_;
  const std::array<double, 3> bias = parameters_.rotation_bias;
  const FloorPriorState::Anchors anchors = floor_.anchors();
  const double scale = parameters_.odometry_scale, cost = summary_->final_cost;
  const std::string solver_report = summary_->solver_report;
  const bool converged = summary_->converged;
  auto restore = [&] {
    parameters_.poses = poses;
    *landmarks_ = landmarks;
    parameters_.rotation_bias = bias;
    floor_.set_anchors(anchors);
    parameters_.odometry_scale = scale;
  };
  auto cost_at = [&](double target, double tolerance, double* result) -> Status {
    restore();
    ScaleMapAboutFirstCamera(target / scale);
    parameters_.hold_scale = true;
    const Status status = Solve(options.robust_loss_scale_px, /*with_lines=*/true, tolerance);
    parameters_.hold_scale = false;
    *result = summary_->final_cost;
    return status;
  };
  const double step =
      setup_.noise.translation_sigma / std::sqrt(static_cast<double>(parameters_.poses.size() - 1));
  const double loose = std::max(options.intermediate_function_tolerance, options.function_tolerance);
  double below = 0, above = 0, found = 0;
  SFM_RETURN_IF_ERROR(cost_at(scale * (1 - step), loose, &below));
  // The centre sample is the last solve itself: that solve converged (at function_tolerance) with
  // lambda free, so with lambda held at its value a solve stops at once (1 iteration on the room
  // loop, the same cost to 1e-6) and would only cost its time.
  const double centre = cost;
  SFM_RETURN_IF_ERROR(cost_at(scale * (1 + step), loose, &above));
  const double x = ParabolaMinimumStep(below, centre, above, /*max_steps=*/2);
  const double target = scale * (1 + x * step);
  SFM_RETURN_IF_ERROR(cost_at(target, options.function_tolerance, &found));
  if (!(found < cost)) {
    restore();
    summary_->final_cost = cost;
    summary_->solver_report = solver_report;
    summary_->converged = converged;
    summary_->floor_prior_report += "; scale line search kept " + std::to_string(scale);
  } else {
    summary_->floor_prior_report +=
        "; scale line search " + std::to_string(scale) + " -> " + std::to_string(target);
  }
  return Status::Ok();
}

void BundleAdjustment::FinishFloorSummary() {
  floor_.Summarise(summary_);
  summary_->odometry_scale = parameters_.odometry_scale;
  summary_->odometry_rotation_bias_rad = parameters_.rotation_bias;
}

Status BundleAdjust(const std::vector<Pose3>& world_T_base_odometry, double odometry_scale_start,
                    const BundleAdjustmentOptions& options, Reconstruction* reconstruction,
                    BundleAdjustmentSummary* summary) {
  BundleAdjustment adjustment(world_T_base_odometry, odometry_scale_start, options, reconstruction, summary);
  Status status = adjustment.Start();
  if (status.ok()) status = adjustment.SolveCoarse();
  if (status.ok()) status = adjustment.SolveFine();
  if (status.ok()) status = adjustment.Filter();
  adjustment.Finish();
  return status;
}

}  // namespace sfm

#include "backend/bundle_adjustment/bundle_adjuster.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "backend/bundle_adjustment/floor_prior.h"
#include "backend/bundle_adjustment/floor_prior_cost.h"
#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/observability.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"
#include "backend/bundle_adjustment/pose_block_cost.h"
#include "backend/bundle_adjustment/pose_parameters.h"

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

// The closest point of the line (point, unit direction) to x.
Eigen::Vector3d ProjectOntoLine(const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                                const Eigen::Vector3d& x) {
  return point + direction * direction.dot(x - point);
}

// Solves after the last joint solve that drop the landmarks it made unobservable, at most
// (docs/bundle_adjustment.md, "Robust loss, stages and outliers", step 7).
constexpr int kObservabilityRounds = 3;

class BundleAdjuster {
 public:
  // `start`: the poses the solves start from (the odometry, or an earlier adjustment's result);
  // `odometry`: the measurements of the odometry prior.
  BundleAdjuster(const Calibration& calibration, const std::vector<Pose3>& odometry,
                 const std::vector<Pose3>& start, double start_scale, const BundleAdjustmentOptions& options,
                 Landmarks* landmarks, BundleAdjustmentSummary* summary)
      : camera_(calibration.base_T_camera, calibration.camera.fx, calibration.camera.fy,
                calibration.camera.cx, calibration.camera.cy),
        base_T_camera_(calibration.base_T_camera),
        K_(calibration.camera.K()),
        noise_(calibration.odometry_noise),
        odometry_(odometry),
        options_(options),
        landmarks_(landmarks),
        summary_(summary),
        odometry_scale_(start_scale),
        with_bias_(EstimatesRotationBias(options, calibration.base_T_camera, odometry)) {
    for (const Pose3& pose : start) poses_.push_back(PoseParameters::FromPose(pose));
  }

  // Whether the odometry's rotation bias is in the problem: asked for, or (auto) wherever the floor
  // prior may apply, decided on the rig and the odometry before any solve (docs/bundle_adjustment.md,
  // "Floor scale bias").
  static bool EstimatesRotationBias(const BundleAdjustmentOptions& options, const Pose3& base_T_camera,
                                    const std::vector<Pose3>& odometry) {
    if (options.estimate_odometry_rotation_bias) return true;
    return options.estimate_odometry_rotation_bias_on_floor && options.floor_prior != FloorPriorMode::kOff &&
           FloorPriorRigProblem(base_T_camera, odometry, options.floor_sigma_m).empty();
  }
  bool EstimatesRotationBias() const { return with_bias_; }

  Status Run(const MapHook& map_hook = MapHook()) {
    summary_->frames = static_cast<int>(poses_.size());
    DropUnusableObservations();
    RemoveLandmarksWithFewViews();
    DropUnobservableLandmarks(/*refined=*/false);
    summary_->points = static_cast<int>(landmarks_->points.size());
    summary_->lines = static_cast<int>(landmarks_->lines.size());
    summary_->observations = CountObservations();
    if (poses_.size() < 2 || summary_->observations == 0) {
      summary_->solver_report = "nothing to solve: no observable landmark in two frames";
      return Status::Ok();
    }
    // 1. Poses and points at the coarse loss scale: from the odometry, errors of tens of pixels
    //    are drift, not outliers. Lines are left out: triangulated on drifting poses they start far
    //    worse than points (degrees, decimetres) and trap a joint solve in wrong minima.
    // 2. Each line alone on those poses (with no point, on the odometry's; then a coarse joint
    //    solve refines the poses with the lines before step 3 judges anything by its error).
    // 3. Observations beyond the coarse scale go (that loss already treated them as outliers),
    //    and landmarks that the refined poses show unobservable (the odometry's drift can hide a
    //    line parallel to the motion; a near-degenerate landmark makes the joint system singular).
    // 4. Everything at the fine loss scale, then the outlier rounds.
    const double coarse_scale_px = std::max(options_.coarse_loss_scale_px, options_.robust_loss_scale_px);
    if (!landmarks_->points.empty()) {
      SFM_RETURN_IF_ERROR(Solve(coarse_scale_px, /*with_lines=*/false, options_.function_tolerance));
    }
    RefineLinesOnFixedPoses(coarse_scale_px);
    if (landmarks_->points.empty()) {
      SFM_RETURN_IF_ERROR(Solve(coarse_scale_px, /*with_lines=*/true, options_.function_tolerance));
    }
    RemoveOutliers(std::max(coarse_scale_px, options_.outlier_threshold_px));
    RemoveLandmarksWithFewViews();
    DropUnobservableLandmarks(/*refined=*/true);
    if (CountObservations() == 0) return RevertToOdometry("no landmark left observable on the refined poses");
    // 5. The floor prior, decided on the coarse map (its floor is where the odometry's scale put it).
    SelectFloor(/*first=*/true);
    // A solve that an outlier round follows stops at the looser intermediate tolerance; the
    // returned result always comes from a solve at function_tolerance.
    bool loose = options_.outlier_rounds > 0;
    SFM_RETURN_IF_ERROR(Solve(options_.robust_loss_scale_px, /*with_lines=*/true,
                              loose ? options_.intermediate_function_tolerance : options_.function_tolerance));
    // The caller's change of the fine map (track extension), before the outlier rounds, which judge
    // the new observations as the old ones, and whose solves refine it with the poses.
    if (map_hook.change) {
      map_hook.change(RefinedPoses(), landmarks_);
      DropUnusableObservations();
      RemoveLandmarksWithFewViews();
      DropUnobservableLandmarks(/*refined=*/true);
      if (CountObservations() == 0) return RevertToOdometry("no landmark left after the map's change");
      SelectFloor(/*first=*/false);
      if (options_.outlier_rounds == 0) {
        SFM_RETURN_IF_ERROR(Solve(options_.robust_loss_scale_px, /*with_lines=*/true, options_.function_tolerance));
      }
    }
    for (int round = 0; round < options_.outlier_rounds; ++round) {
      const int outliers = RemoveOutliers(options_.outlier_threshold_px);
      RemoveLandmarksWithFewViews();
      const int unobservable = DropUnobservableLandmarks(/*refined=*/true);
      if (outliers + unobservable == 0) break;
      if (CountObservations() == 0) return RevertToOdometry("every landmark was removed after solving");
      SelectFloor(/*first=*/false);  // the removals renumbered the landmarks; the map was rescaled
      loose = round + 1 < options_.outlier_rounds;
      SFM_RETURN_IF_ERROR(Solve(options_.robust_loss_scale_px, /*with_lines=*/true,
                                loose ? options_.intermediate_function_tolerance : options_.function_tolerance));
    }
    if (loose) {
      SFM_RETURN_IF_ERROR(Solve(options_.robust_loss_scale_px, /*with_lines=*/true, options_.function_tolerance));
    }
    // 6. The last solve's own landmarks under the rules every earlier solve's passed: a landmark it
    //    made unobservable (on Strecha, lines slid behind or through a camera, which their images
    //    cannot show, and still holding the poses) is dropped, and the rest solved again.
    for (int round = 0; round < kObservabilityRounds; ++round) {
      const int unobservable = DropUnobservableLandmarks(/*refined=*/true);
      RemoveLandmarksWithFewViews();
      if (unobservable == 0) break;
      summary_->landmarks_unobservable_after_last_solve += unobservable;
      ++summary_->observability_solves;
      if (CountObservations() == 0) return RevertToOdometry("every landmark was removed after solving");
      SelectFloor(/*first=*/false);
      SFM_RETURN_IF_ERROR(Solve(options_.robust_loss_scale_px, /*with_lines=*/true, options_.function_tolerance));
    }
    if (options_.floor_scale_line_search) SFM_RETURN_IF_ERROR(SearchScale());
    ComputeRms();
    FinishFloorSummary();
    return Status::Ok();
  }

  // With no landmark left, the poses they gave are no better than the odometry's.
  Status RevertToOdometry(const std::string& why) {
    for (size_t f = 0; f < poses_.size(); ++f) poses_[f] = PoseParameters::FromPose(odometry_[f]);
    odometry_scale_ = 1;
    rotation_bias_ = {0, 0, 0};
    floor_.points.clear();
    floor_.lines.clear();
    FinishFloorSummary();
    summary_->solver_report = why + "; the trajectory is the odometry's";
    return Status::Ok();
  }

  std::vector<Pose3> RefinedPoses() const {
    std::vector<Pose3> poses;
    for (const PoseParameters& pose : poses_) poses.push_back(pose.ToPose());
    return poses;
  }

 private:
  // The floor prior's decision and selection (docs/bundle_adjustment.md, "Floor prior"). `first`:
  // on the coarse map, where the rig and the odometry are checked and the plane's height must
  // agree with the odometry's noise model (auto); later, on the map the prior has rescaled, the
  // landmarks are selected again about the plane found there.
  void SelectFloor(bool first) {
    if (options_.floor_prior == FloorPriorMode::kOff) {
      if (first) summary_->floor_prior_report = "floor prior off (--floor_prior=off)";
      return;
    }
    if (!first && !scale_free_) return;  // not applied in the first place
    const bool automatic = options_.floor_prior == FloorPriorMode::kAuto;
    const double sigma_m = options_.floor_sigma_m;
    const double camera_height_m = base_T_camera_.translation.z();
    auto skip = [&](const std::string& why) {
      summary_->floor_prior_report = first ? "floor prior not applied: " + why
                                           : "floor prior dropped after the outlier round, the odometry scale " +
                                                 std::to_string(odometry_scale_) + " it gave kept: " + why;
      floor_.points.clear();
      floor_.lines.clear();
    };
    if (first) {
      const std::string rig_problem = FloorPriorRigProblem(base_T_camera_, odometry_, sigma_m);
      // Even when forced on, a floor must be below the camera.
      if (!rig_problem.empty() && (automatic || !(camera_height_m > 0))) return skip(rig_problem);
      // The base poses are held on the floor only where the odometry shows them there.
      base_on_floor_ = options_.floor_base_prior && rig_problem.empty();
    }
    double camera_z_m = 0;
    for (const PoseParameters& pose : poses_) camera_z_m += (pose.ToPose() * base_T_camera_).translation.z();
    camera_z_m /= poses_.size();
    const double half_width_m = 3 * sigma_m;
    // After the first selection the prior has pulled the floor it chose to z = 0: look for it
    // there, not again from below (stray landmarks under the floor may then gather in a slab).
    FloorPlane plane = FindFloorPlane(*landmarks_, camera_z_m, half_width_m, options_.floor_min_landmarks,
                                      first ? std::nullopt : std::optional<double>(0.0));
    if (!plane.found) return skip(plane.why);
    const double allowed_m = AllowedFloorHeight();
    if (automatic && plane.z_m < -allowed_m) {
      // Mis-triangulated landmarks under the floor can gather in a slab, but not outnumber the
      // floor: a plane where the noise model allows it, holding more, is the floor.
      const FloorPlane allowed = FindFloorPlane(*landmarks_, camera_z_m, half_width_m, options_.floor_min_landmarks,
                                                std::nullopt, -allowed_m);
      if (allowed.found && std::abs(allowed.z_m) <= allowed_m && allowed.support > plane.support) {
        stray_slab_note_ = "; a slab of " + std::to_string(plane.support) + " landmarks at z = " +
                           std::to_string(plane.z_m) + " m below it taken for stray";
        plane = allowed;
      }
    }
    if (first) summary_->floor_plane_z_m = plane.z_m;
    if (automatic && !(std::abs(plane.z_m) <= allowed_m)) {
      return skip("the lowest horizontal plane (" + std::to_string(plane.support) + " landmarks) is at z = " +
                  std::to_string(plane.z_m) + " m, beyond the " + std::to_string(allowed_m) +
                  " m the odometry's scale sigma allows: the base origin is not on the floor");
    }
    floor_ = SelectFloorLandmarks(*landmarks_, plane.z_m, half_width_m);
    floor_anchors_.clear();
    for (int line : floor_.lines) {
      floor_anchors_.push_back({landmarks_->lines[line].end0, landmarks_->lines[line].end1});
    }
    scale_free_ = true;
    summary_->floor_prior_report = "floor prior: plane at z = " + std::to_string(plane.z_m) + " m (" +
                                   std::to_string(plane.support) + " of " + std::to_string(plane.below_camera) +
                                   " landmarks below the cameras), " + std::to_string(floor_.points.size()) +
                                   " points and " + std::to_string(floor_.lines.size()) + " lines held" +
                                   (base_on_floor_ ? ", base poses held on it" : "") + stray_slab_note_;
  }

  // How far from z = 0 the floor of a map at the odometry's scale may be: a map whose trajectory is
  // s times too long has its floor at (1 - s) * camera height (the map scaled about the cameras,
  // which the rig holds at their height); the noise model allows |s - 1| up to 3 translation
  // sigmas, and the slab's half width (3 floor sigmas) is the plane's own resolution.
  double AllowedFloorHeight() const {
    return 3 * noise_.translation_sigma * base_T_camera_.translation.z() + 3 * options_.floor_sigma_m;
  }

  // The map scaled by `gain` about the first camera's centre (its pose is held): the cameras'
  // centres (rotations kept), every landmark, the floor lines' anchors and the odometry's scale
  // factor. The images see no change (cameras at the first camera's height keep it); only the
  // floor's height and the scale prior do.
  void ScaleMapAboutFirstCamera(double gain) {
    const Eigen::Vector3d centre = (poses_[0].ToPose() * base_T_camera_).translation;
    for (size_t f = 1; f < poses_.size(); ++f) {
      Pose3 camera = poses_[f].ToPose() * base_T_camera_;
      camera.translation = centre + gain * (camera.translation - centre);
      poses_[f] = PoseParameters::FromPose(camera * base_T_camera_.Inverse());
    }
    ScaleLandmarksAbout(centre, gain, landmarks_);
    for (auto& anchors : floor_anchors_) {
      for (Eigen::Vector3d& anchor : anchors) anchor = centre + gain * (anchor - centre);
    }
    odometry_scale_ *= gain;
  }

  // The line search on the odometry's scale factor after the last joint solve
  // (floor_scale_line_search; docs/bundle_adjustment.md, "Floor scale bias: the start and the line
  // search"). The joint solves stop, by their function tolerance, with the scale part-way along its
  // shallow direction; with lambda held, the same solves converge. So: the map scaled to lambda (1 - d)
  // and lambda (1 + d), each solved with lambda held (at the intermediate tolerance), a parabola
  // through their costs and the last solve's at lambda, and the map solved once more (at function_tolerance)
  // at its minimum, at most 2 d away (where the three samples still describe the cost). d is lambda's
  // standard error through the per-step priors, translation_sigma / sqrt(steps): the change of
  // scale the odometry itself cannot tell. The result is kept only if its cost is below the last
  // solve's.
  Status SearchScale() {
    if (!scale_free_ || (floor_.points.empty() && floor_.lines.empty()) || poses_.size() < 2) return Status::Ok();
    const std::vector<PoseParameters> poses = poses_;
    const Landmarks landmarks = *landmarks_;
    const std::array<double, 3> bias = rotation_bias_;
    const std::vector<std::array<Eigen::Vector3d, 2>> anchors = floor_anchors_;
    const double scale = odometry_scale_, cost = summary_->final_cost;
    const std::string solver_report = summary_->solver_report;
    const bool converged = summary_->converged;
    auto restore = [&] {
      poses_ = poses;
      *landmarks_ = landmarks;
      rotation_bias_ = bias;
      floor_anchors_ = anchors;
      odometry_scale_ = scale;
    };
    auto cost_at = [&](double target, double tolerance, double* result) -> Status {
      restore();
      ScaleMapAboutFirstCamera(target / scale);
      hold_scale_ = true;
      const Status status = Solve(options_.robust_loss_scale_px, /*with_lines=*/true, tolerance);
      hold_scale_ = false;
      *result = summary_->final_cost;
      return status;
    };
    const double step = noise_.translation_sigma / std::sqrt(static_cast<double>(poses_.size() - 1));
    const double loose = std::max(options_.intermediate_function_tolerance, options_.function_tolerance);
    double below = 0, centre = 0, above = 0, found = 0;
    SFM_RETURN_IF_ERROR(cost_at(scale * (1 - step), loose, &below));
    // The centre sample is the last solve itself: that solve converged (at function_tolerance) with
    // lambda free, so with lambda held at its value a solve stops at once (1 iteration on the room
    // loop, the same cost to 1e-6) and would only cost its time.
    centre = cost;
    SFM_RETURN_IF_ERROR(cost_at(scale * (1 + step), loose, &above));
    const double x = ParabolaMinimumStep(below, centre, above, /*max_steps=*/2);
    const double target = scale * (1 + x * step);
    SFM_RETURN_IF_ERROR(cost_at(target, options_.function_tolerance, &found));
    if (!(found < cost)) {
      restore();
      summary_->final_cost = cost;
      summary_->solver_report = solver_report;
      summary_->converged = converged;
      scale_search_note_ = "; scale line search kept " + std::to_string(scale);
    } else {
      scale_search_note_ = "; scale line search " + std::to_string(scale) + " -> " + std::to_string(target);
    }
    summary_->floor_prior_report += scale_search_note_;
    return Status::Ok();
  }

  // The odometry's scale factor is a block of the problem: freed by the floor prior, or held at a
  // start scale an earlier adjustment's floor gave.
  bool ScaleInProblem() const { return scale_free_ || odometry_scale_ != 1.0; }

  void FinishFloorSummary() {
    summary_->floor_prior_used = scale_free_ && !(floor_.points.empty() && floor_.lines.empty());
    summary_->floor_points = static_cast<int>(floor_.points.size());
    summary_->floor_lines = static_cast<int>(floor_.lines.size());
    summary_->floor_point_indices = floor_.points;
    summary_->floor_line_indices = floor_.lines;
    summary_->odometry_scale = odometry_scale_;
    summary_->odometry_rotation_bias_rad = rotation_bias_;
  }

  // The residuals of one observation at the current parameters; false when it cannot be evaluated.
  bool PointResiduals(const PointLandmark& point, const PointObservation& observation,
                      Eigen::Vector2d* r) const {
    const PoseParameters& pose = poses_[observation.frame];
    return PointReprojectionCost(camera_, observation.pixel)(pose.rotation.data(), pose.translation.data(),
                                                             point.position.data(), r->data()) &&
           Finite(*r);
  }
  bool LineResiduals(const OrthonormalLine& line, const LineObservation& observation,
                     Eigen::Vector2d* r) const {
    const PoseParameters& pose = poses_[observation.frame];
    return LineReprojectionCost(camera_, observation.p0, observation.p1)(
               pose.rotation.data(), pose.translation.data(), line.data(), r->data()) &&
           Finite(*r);
  }

  int CountObservations() const {
    int count = 0;
    for (const PointLandmark& point : landmarks_->points)
      count += static_cast<int>(point.observations.size());
    for (const LineLandmark& line : landmarks_->lines) count += static_cast<int>(line.observations.size());
    return count;
  }

  // Removes the observations that `keep` rejects; returns how many.
  template <typename Landmark, typename Keep>
  static int RemoveObservations(Landmark* landmark, Keep keep) {
    auto& observations = landmark->observations;
    const size_t before = observations.size();
    observations.erase(std::remove_if(observations.begin(), observations.end(),
                                      [&keep](const auto& observation) { return !keep(observation); }),
                       observations.end());
    return static_cast<int>(before - observations.size());
  }

  void DropUnusableObservations() {
    Eigen::Vector2d r;
    for (PointLandmark& point : landmarks_->points) {
      summary_->observations_unusable += RemoveObservations(&point, [&](const PointObservation& observation) {
        return PointResiduals(point, observation, &r);
      });
    }
    for (LineLandmark& line : landmarks_->lines) {
      const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
      summary_->observations_unusable += RemoveObservations(&line, [&](const LineObservation& observation) {
        return LineResiduals(parameters, observation, &r);
      });
    }
  }

  // Removes the landmarks that `keep_point` / `keep_line` reject, renumbering point_landmark.
  // Returns the numbers of points and lines removed.
  template <typename KeepPoint, typename KeepLine>
  std::pair<int, int> RemoveLandmarks(KeepPoint keep_point, KeepLine keep_line) {
    std::vector<PointLandmark>& points = landmarks_->points;
    std::vector<int> new_index(points.size(), -1);
    size_t kept = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      if (!keep_point(points[i])) continue;
      new_index[i] = static_cast<int>(kept);
      if (kept != i) points[kept] = std::move(points[i]);
      ++kept;
    }
    const int points_removed = static_cast<int>(points.size() - kept);
    points.resize(kept);
    std::vector<LineLandmark>& lines = landmarks_->lines;
    const size_t lines_before = lines.size();
    lines.erase(std::remove_if(lines.begin(), lines.end(),
                               [&](const LineLandmark& line) { return !keep_line(line); }),
                lines.end());
    for (LineLandmark& line : lines) {
      if (line.point_landmark >= 0) line.point_landmark = new_index[line.point_landmark];
    }
    return {points_removed, static_cast<int>(lines_before - lines.size())};
  }

  void RemoveLandmarksWithFewViews() {
    const auto [points, lines] =
        RemoveLandmarks([](const PointLandmark& point) { return point.observations.size() >= 2; },
                        [](const LineLandmark& line) { return line.observations.size() >= 2; });
    summary_->points_removed += points;
    summary_->lines_removed += lines;
  }

  template <typename Observations>
  std::vector<Pose3> CameraPoses(const Observations& observations) const {
    std::vector<Pose3> cameras;
    for (const auto& observation : observations) {
      cameras.push_back(poses_[observation.frame].ToPose() * base_T_camera_);
    }
    return cameras;
  }
  static std::vector<Eigen::Vector3d> Centres(const std::vector<Pose3>& cameras) {
    std::vector<Eigen::Vector3d> centres;
    for (const Pose3& camera : cameras) centres.push_back(camera.translation);
    return centres;
  }

  // Returns the number of landmarks dropped. `refined`: the landmarks and poses have been solved
  // for, so the depth floor applies too. Not before the first solve: landmarks triangulated on
  // drifting odometry can start within min_depth_m of a camera (or behind it) and be fine after
  // it (the triangulation already held them to the floor on the odometry's poses).
  int DropUnobservableLandmarks(bool refined) {
    const auto [points, lines] = RemoveLandmarks(
        [&](const PointLandmark& point) {
          const std::vector<Pose3> cameras = CameraPoses(point.observations);
          return (!refined || SmallestDepth({point.position}, cameras) >= options_.min_depth_m) &&
                 PointTriangulationAngleDeg(point.position, Centres(cameras)) >=
                     options_.min_point_triangulation_angle_deg;
        },
        [&](const LineLandmark& line) {
          const std::vector<Pose3> cameras = CameraPoses(line.observations);
          for (size_t i = 0; refined && i < cameras.size(); ++i) {
            const LineObservation& observation = line.observations[i];
            if (!(ObservedLineDepth(K_, cameras[i], observation.p0, observation.p1, line.point,
                                    line.direction) >= options_.min_depth_m)) {
              return false;
            }
          }
          // The estimate of a degenerate line can be anywhere (its triangulation has no unique
          // solution), so the planes of its image lines must also meet at a large enough angle.
          std::vector<Eigen::Vector3d> normals;
          for (size_t i = 0; i < line.observations.size(); ++i) {
            const LineObservation& observation = line.observations[i];
            normals.push_back(BackProjectedPlaneNormal(K_, cameras[i].RotationMatrix(), observation.p0,
                                                       observation.p1));
          }
          const double angle_deg =
              std::min(LineTriangulationAngleDeg(line.point, line.direction, Centres(cameras)),
                       LargestPlaneAngleDeg(normals));
          return angle_deg >= options_.min_line_triangulation_angle_deg;
        });
    summary_->points_unobservable += points;
    summary_->lines_unobservable += lines;
    return points + lines;
  }

  ceres::LinearSolverType LinearSolverType() const {
    switch (options_.linear_solver) {
      case BundleAdjustmentLinearSolver::kDenseSchur:
        return ceres::DENSE_SCHUR;
      case BundleAdjustmentLinearSolver::kSparseSchur:
        return ceres::SPARSE_SCHUR;
      case BundleAdjustmentLinearSolver::kAuto:
        break;
    }
    return static_cast<int>(poses_.size()) <= options_.dense_schur_max_frames ? ceres::DENSE_SCHUR
                                                                              : ceres::SPARSE_SCHUR;
  }

  std::unique_ptr<ceres::LossFunction> MakeLoss(double scale_px) const {
    if (options_.robust_loss == RobustLoss::kHuber) return std::make_unique<ceres::HuberLoss>(scale_px);
    return std::make_unique<ceres::CauchyLoss>(scale_px);
  }

  ceres::Solver::Options SolverOptions(ceres::LinearSolverType type) const {
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = type;
    solver_options.max_num_iterations = options_.max_iterations;
    solver_options.num_threads = options_.num_threads;
    solver_options.logging_type = ceres::SILENT;
    return solver_options;
  }

  // Each line alone, the poses held where they are (one small problem per line, 4 unknowns). A
  // line whose solve fails keeps its estimate. `subset`: only those lines (indices), else all.
  // Returns the sum of their final costs (Ceres's, 1/2 sum of the loss).
  double RefineLinesOnFixedPoses(double loss_scale_px, const std::vector<int>* subset = nullptr) {
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(loss_scale_px);
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    const ceres::Solver::Options solver_options = SolverOptions(ceres::DENSE_QR);
    const size_t count = subset ? subset->size() : landmarks_->lines.size();
    double cost = 0;
    for (size_t k = 0; k < count; ++k) {
      LineLandmark& line = landmarks_->lines[subset ? (*subset)[k] : k];
      OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
      ceres::Problem problem(problem_options);
      problem.AddParameterBlock(parameters.data(), 6, &line_manifold_);
      for (const LineObservation& observation : line.observations) {
        PoseParameters& pose = poses_[observation.frame];
        problem.AddResidualBlock(LineReprojectionCost::Create(camera_, observation.p0, observation.p1),
                                 loss.get(), pose.rotation.data(), pose.translation.data(),
                                 parameters.data());
        problem.SetParameterBlockConstant(pose.rotation.data());
        problem.SetParameterBlockConstant(pose.translation.data());
      }
      ceres::Solver::Summary ceres_summary;
      ceres::Solve(solver_options, &problem, &ceres_summary);
      if (ceres_summary.IsSolutionUsable()) {
        WriteBackLine(parameters, &line);
        cost += ceres_summary.final_cost;
      } else {
        cost += ceres_summary.initial_cost;
      }
    }
    VLOG(1) << "bundle adjustment: " << count << " lines solved alone on fixed poses in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s";
    return cost;
  }

  // The lines of a joint solve (`joint`, indices in order) and those solved apart after it: a line with exactly two views has 4 residuals (the two
  // end-point distances per view) for its 4 degrees of freedom; on any poses it fits both views
  // exactly (the line where its two back-projected planes meet, which the observability check
  // keeps at an angle), so its least cost is 0 on every pose and the joint minimum over the poses
  // is the same without it. The floor prior's lines stay: their prior is a fifth and sixth
  // residual, which the poses must then satisfy too.
  void SplitLines(std::vector<int>* joint, std::vector<int>* apart) const {
    std::vector<bool> on_floor(landmarks_->lines.size(), false);
    if (scale_free_) {
      for (int line : floor_.lines) on_floor[line] = true;
    }
    for (size_t i = 0; i < landmarks_->lines.size(); ++i) {
      const bool two_view = landmarks_->lines[i].observations.size() == 2;
      (two_view && !on_floor[i] ? apart : joint)
          ->push_back(static_cast<int>(i));
    }
  }

  // Adds `cost` on `blocks` to the joint problem; a pose among the blocks is its rotation's and
  // translation's pointers, next to each other. Each such pair is given to Ceres as the pose's one
  // 7-number block (PoseBlockCost: the same residuals and Jacobian entries, a quarter of the Schur
  // complement's cells).
  void AddResidual(ceres::Problem* problem, ceres::CostFunction* cost, ceres::LossFunction* loss,
                   const std::vector<double*>& blocks) const {
    std::vector<int> pose_starts;
    std::vector<double*> outer_blocks;
    for (size_t k = 0; k < blocks.size(); ++k) {
      outer_blocks.push_back(blocks[k]);
      if (k + 1 < blocks.size() && IsPoseRotation(blocks[k]) && blocks[k + 1] == blocks[k] + 4) {
        pose_starts.push_back(static_cast<int>(k));
        ++k;
      }
    }
    problem->AddResidualBlock(new PoseBlockCost(cost, pose_starts), loss, outer_blocks);
  }
  bool IsPoseRotation(const double* block) const {
    for (const PoseParameters& pose : poses_) {
      if (block == pose.rotation.data()) return true;
    }
    return false;
  }

  // Poses, points and (with_lines) lines together, until Ceres's function_tolerance.
  Status Solve(double loss_scale_px, bool with_lines, double function_tolerance) {
    const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(loss_scale_px);
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();

    // A pose is one block: the 7 numbers from its rotation on (see AddResidual).
    for (PoseParameters& pose : poses_) {
      problem.AddParameterBlock(pose.rotation.data(), 7, &pose_manifold_);
      ordering->AddElementToGroup(pose.rotation.data(), 1);
    }
    problem.SetParameterBlockConstant(poses_[0].rotation.data());

    // Every landmark's parameters in one buffer, points then lines, in their order: Ceres orders
    // the blocks of an ordering group by address (a std::set<double*>), and that order is the
    // Schur eliminator's summation order. In a buffer it is the landmarks' order, not the heap's,
    // so that a run gives the same numbers every time.
    // Lines: all (with_lines), or all but the two-view lines solved apart after the solve.
    // joint_slot: a line's place among the problem's lines, or -1.
    std::vector<int> joint_lines, apart_lines;
    if (with_lines) SplitLines(&joint_lines, &apart_lines);
    std::vector<int> joint_slot(landmarks_->lines.size(), -1);
    for (size_t k = 0; k < joint_lines.size(); ++k) joint_slot[joint_lines[k]] = static_cast<int>(k);
    const size_t point_count = landmarks_->points.size();
    const size_t line_count = joint_lines.size();
    std::vector<double> landmark_values(3 * point_count + 6 * line_count);
    auto point_block = [&](size_t i) { return landmark_values.data() + 3 * i; };
    auto line_block = [&](size_t i) { return landmark_values.data() + 3 * point_count + 6 * i; };
    for (size_t i = 0; i < point_count; ++i) {
      const PointLandmark& point = landmarks_->points[i];
      double* position = point_block(i);
      std::copy(point.position.data(), point.position.data() + 3, position);
      for (const PointObservation& observation : point.observations) {
        PoseParameters& pose = poses_[observation.frame];
        AddResidual(&problem, PointReprojectionCost::Create(camera_, observation.pixel), loss.get(),
                    {pose.rotation.data(), pose.translation.data(), position});
      }
      ordering->AddElementToGroup(position, 0);
    }

    for (size_t i = 0; i < line_count; ++i) {
      const LineLandmark& line = landmarks_->lines[joint_lines[i]];
      double* parameters = line_block(i);
      const OrthonormalLine initial = OrthonormalLineFromPointDirection(line.point, line.direction);
      std::copy(initial.begin(), initial.end(), parameters);
      problem.AddParameterBlock(parameters, 6, &line_manifold_);
      for (const LineObservation& observation : line.observations) {
        PoseParameters& pose = poses_[observation.frame];
        AddResidual(&problem, LineReprojectionCost::Create(camera_, observation.p0, observation.p1),
                    loss.get(), {pose.rotation.data(), pose.translation.data(), parameters});
      }
      ordering->AddElementToGroup(parameters, 0);
    }

    // The floor prior (whitened by floor_sigma_m; Huber at one sigma, so that a landmark selected
    // off the floor pulls with a bounded force) and the odometry's scale factor it observes.
    ceres::HuberLoss floor_loss(1.0);
    // A start from an earlier adjustment that the floor prior rescaled (start_scale != 1) keeps
    // that scale in the odometry priors, held, until this run's floor frees it: otherwise the
    // first solves would pull the start back to the odometry's scale.
    const bool scaled = ScaleInProblem();
    if (scaled) {
      problem.AddParameterBlock(&odometry_scale_, 1);
      ordering->AddElementToGroup(&odometry_scale_, 1);
      if (!scale_free_ || hold_scale_) problem.SetParameterBlockConstant(&odometry_scale_);
    }
    if (scale_free_) {
      for (int point : floor_.points) {
        problem.AddResidualBlock(FloorPointCost::Create(options_.floor_sigma_m), &floor_loss, point_block(point));
      }
      for (size_t k = 0; with_lines && k < floor_.lines.size(); ++k) {
        problem.AddResidualBlock(
            FloorLineCost::Create(floor_anchors_[k][0], floor_anchors_[k][1], options_.floor_sigma_m),
            &floor_loss, line_block(joint_slot[floor_.lines[k]]));
      }
      if (base_on_floor_) {
        // The first pose is held constant; its prior would be a constant.
        const double tilt_sigma_rad = options_.floor_sigma_m / base_T_camera_.translation.z();
        for (size_t f = 1; f < poses_.size(); ++f) {
          AddResidual(&problem, BaseOnFloorCost::Create(options_.floor_sigma_m, tilt_sigma_rad), nullptr,
                      {poses_[f].rotation.data(), poses_[f].translation.data()});
        }
      }
      problem.AddResidualBlock(OdometryScalePriorCost::Create(noise_.translation_sigma), nullptr, &odometry_scale_);
      // With nothing on the floor left, the scale it gave is kept.
      if (floor_.points.empty() && (!with_lines || floor_.lines.empty())) {
        problem.SetParameterBlockConstant(&odometry_scale_);
      }
    }

    // The odometry's rotation bias: a zero-mean prior with the noise model's per-frame rotation
    // sigma (a bias larger than the whole per-frame noise the model states is outside the model;
    // the steps' vision-determined rotations pin it far tighter, about sigma / sqrt(steps)).
    double* const bias = rotation_bias_.data();
    if (with_bias_) {
      problem.AddParameterBlock(bias, 3);
      ordering->AddElementToGroup(bias, 1);
      problem.AddResidualBlock(OdometryRotationBiasPriorCost::Create(noise_.rotation_sigma), nullptr, bias);
    }
    for (size_t f = 0; f + 1 < poses_.size(); ++f) {
      const Pose3 motion = odometry_[f].Inverse() * odometry_[f + 1];
      const OdometryStepSigmas sigmas = OdometryStepSigmasFor(motion.translation.norm(), noise_, options_);
      std::vector<double*> blocks = {poses_[f].rotation.data(), poses_[f].translation.data(),
                                     poses_[f + 1].rotation.data(), poses_[f + 1].translation.data()};
      ceres::CostFunction* cost = nullptr;
      if (with_bias_ && scaled) {
        cost = OdometryPriorWithScaleAndBiasCost::Create(motion, noise_.rotation_sigma, sigmas.along_m,
                                                         sigmas.across_m);
        blocks.insert(blocks.end(), {&odometry_scale_, bias});
      } else if (with_bias_) {
        cost =
            OdometryPriorWithBiasCost::Create(motion, noise_.rotation_sigma, sigmas.along_m, sigmas.across_m);
        blocks.push_back(bias);
      } else if (scaled) {
        cost = OdometryPriorWithScaleCost::Create(motion, noise_.rotation_sigma, sigmas.along_m,
                                                  sigmas.across_m);
        blocks.push_back(&odometry_scale_);
      } else {
        cost = OdometryPriorCost::Create(motion, noise_.rotation_sigma, sigmas.along_m, sigmas.across_m);
      }
      AddResidual(&problem, cost, nullptr, blocks);
    }

    ceres::Solver::Options solver_options = SolverOptions(LinearSolverType());
    solver_options.linear_solver_ordering = ordering;
    solver_options.function_tolerance = function_tolerance;
    // With lines, the steps crawl (for tens of iterations on the room loop, each lowering the cost
    // by about 2e-6 relative, 0.4 of the predicted decrease: the landmarks' nonlinearity); Ceres's
    // inner iterations re-solve each landmark on the step's poses and end the solve in a few.
    solver_options.use_inner_iterations = with_lines;
    if (solver_options.use_inner_iterations) solver_options.inner_iteration_ordering = InnerIterationOrdering(landmark_values);
    // Ceres switches the inner iterations off for the rest of a solve once one of them lowers the
    // cost by less than inner_iteration_tolerance (relative, 1e-3 by default); the crawl then
    // resumes (corridor: 38 iterations of the solve after the outlier round, against 5). A gain
    // the solve's own stopping rule still counts keeps them on.
    solver_options.inner_iteration_tolerance = function_tolerance;
    ceres::Solver::Summary ceres_summary;
    ceres::Solve(solver_options, &problem, &ceres_summary);
    if (!ceres_summary.IsSolutionUsable()) {
      return Status::Error("bundle adjustment: Ceres failed: " + ceres_summary.message);
    }
    // Where a solve's time goes (docs/backend_results.md, "Session 6: the back end's time").
    VLOG(1) << "bundle adjustment solve: loss " << loss_scale_px << " px, " << (with_lines ? "lines, " : "")
            << (apart_lines.empty() ? "" : std::to_string(apart_lines.size()) + " two-view lines apart, ")
            << (hold_scale_ ? "scale held, " : "") << "tolerance " << function_tolerance << ": "
            << ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps
            << " iterations, cost " << ceres_summary.initial_cost << " -> " << ceres_summary.final_cost
            << "; " << ceres_summary.total_time_in_seconds << " s (preprocessor "
            << ceres_summary.preprocessor_time_in_seconds << ", residuals "
            << ceres_summary.residual_evaluation_time_in_seconds << ", jacobians "
            << ceres_summary.jacobian_evaluation_time_in_seconds << ", linear solver "
            << ceres_summary.linear_solver_time_in_seconds << ", inner iterations "
            << ceres_summary.inner_iteration_time_in_seconds << ")";

    if (summary_->solves == 0) {
      summary_->initial_cost = ceres_summary.initial_cost;
      summary_->converged = true;
    }
    ++summary_->solves;
    summary_->iterations += ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
    VLOG(2) << "solve: " << ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps
            << " iterations at loss scale " << loss_scale_px << " px" << (with_lines ? " with lines, " : ", ")
            << ceres_summary.total_time_in_seconds << " s";
    summary_->final_cost = ceres_summary.final_cost;
    summary_->converged = summary_->converged && ceres_summary.termination_type == ceres::CONVERGENCE;
    summary_->solver_report = ceres_summary.BriefReport();

    for (size_t i = 0; i < point_count; ++i) landmarks_->points[i].position = Eigen::Map<Eigen::Vector3d>(point_block(i));
    for (size_t i = 0; i < line_count; ++i) {
      OrthonormalLine parameters;
      std::copy(line_block(i), line_block(i) + 6, parameters.begin());
      WriteBackLine(parameters, &landmarks_->lines[joint_lines[i]]);
    }
    // The two-view lines on the solve's poses: their least cost there (about 0) completes the
    // solve's cost, which the scale line search compares.
    if (!apart_lines.empty()) summary_->final_cost += RefineLinesOnFixedPoses(loss_scale_px, &apart_lines);
    return Status::Ok();
  }

  // The group of Ceres's inner iterations: the landmarks (`landmark_values`: the points and lines
  // of the problem, one independent set). After each step every landmark is re-solved on the
  // step's poses, the variable projection of Ruhe & Wedin's algorithm II, which ends the crawl of
  // the joint solves (docs/bundle_adjustment.md, "Solver"). Given explicitly: the ordering Ceres
  // computes when given none comes from hash sets keyed by address, and its groups varied from run
  // to run, and so did the results (docs/bundle_adjustment.md, "Determinism").
  std::shared_ptr<ceres::ParameterBlockOrdering> InnerIterationOrdering(std::vector<double>& landmark_values) {
    auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
    // The landmark blocks start at their sizes' offsets; walk them as Solve laid them out.
    const size_t point_count = landmarks_->points.size();
    for (size_t i = 0; i < point_count; ++i) ordering->AddElementToGroup(landmark_values.data() + 3 * i, 6);
    for (size_t j = 3 * point_count; j < landmark_values.size(); j += 6) {
      ordering->AddElementToGroup(landmark_values.data() + j, 6);
    }
    return ordering;
  }

  void WriteBackLine(const OrthonormalLine& parameters, LineLandmark* line) const {
    Eigen::Vector3d point, direction;
    OrthonormalLineToPointDirection(parameters, &point, &direction);
    if (direction.dot(line->direction) < 0) direction = -direction;
    line->point = point;
    line->direction = direction;
    line->end0 = line->point_landmark >= 0 ? landmarks_->points[line->point_landmark].position
                                           : ProjectOntoLine(point, direction, line->end0);
    line->end1 = ProjectOntoLine(point, direction, line->end1);
  }

  // Removes the observations whose error (norm of the two residuals) exceeds threshold_px.
  int RemoveOutliers(double threshold_px) {
    Eigen::Vector2d r;
    int removed = 0;
    for (PointLandmark& point : landmarks_->points) {
      removed += RemoveObservations(&point, [&](const PointObservation& observation) {
        return PointResiduals(point, observation, &r) && r.norm() <= threshold_px;
      });
    }
    for (LineLandmark& line : landmarks_->lines) {
      const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
      removed += RemoveObservations(&line, [&](const LineObservation& observation) {
        return LineResiduals(parameters, observation, &r) && r.norm() <= threshold_px;
      });
    }
    summary_->observations_removed += removed;
    return removed;
  }

  void ComputeRms() {
    Eigen::Vector2d r;
    double point_sum = 0, line_sum = 0;
    int point_count = 0, line_count = 0;
    for (const PointLandmark& point : landmarks_->points) {
      for (const PointObservation& observation : point.observations) {
        if (!PointResiduals(point, observation, &r)) continue;
        point_sum += r.squaredNorm();
        ++point_count;
      }
    }
    for (const LineLandmark& line : landmarks_->lines) {
      const OrthonormalLine parameters = OrthonormalLineFromPointDirection(line.point, line.direction);
      for (const LineObservation& observation : line.observations) {
        if (!LineResiduals(parameters, observation, &r)) continue;
        line_sum += r.squaredNorm();
        line_count += 2;  // two end-points
      }
    }
    summary_->point_rms_px = point_count > 0 ? std::sqrt(point_sum / point_count) : 0;
    summary_->line_rms_px = line_count > 0 ? std::sqrt(line_sum / line_count) : 0;
  }

  const CameraModel camera_;
  const Pose3 base_T_camera_;
  const Eigen::Matrix3d K_;
  const OdometryNoise noise_;
  const std::vector<Pose3>& odometry_;
  const BundleAdjustmentOptions& options_;
  Landmarks* landmarks_;
  BundleAdjustmentSummary* summary_;
  std::vector<PoseParameters> poses_;
  // The floor prior: applied (the odometry's scale factor is a parameter) or not, the landmarks
  // it holds now, the anchors of those lines (their end-points when selected), the factor.
  bool scale_free_ = false;
  bool base_on_floor_ = false;  // BaseOnFloorCost on every pose but the first while scale_free_
  std::string stray_slab_note_;  // the report's note when the first selection passed over a stray slab
  std::string scale_search_note_;  // the report's note of the scale line search (floor_scale_line_search)
  bool hold_scale_ = false;  // the odometry's scale factor held in Solve (the line search's samples)
  FloorLandmarks floor_;
  std::vector<std::array<Eigen::Vector3d, 2>> floor_anchors_;
  double odometry_scale_ = 1;
  // The odometry's rotation bias b (rad per step, angle-axis in base_i), when estimated.
  std::array<double, 3> rotation_bias_ = {0, 0, 0};
  bool with_bias_ = false;  // EstimatesRotationBias(options, ...), fixed for the run
  PoseManifold pose_manifold_;
  OrthonormalLineManifold line_manifold_;
};

}  // namespace

Status BundleAdjust(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                    const BundleAdjustmentOptions& options, Landmarks* landmarks,
                    std::vector<Pose3>* world_T_base_refined, BundleAdjustmentSummary* summary,
                    const MapHook& map_hook) {
  return BundleAdjust(calibration, world_T_base_odometry, world_T_base_odometry, /*odometry_scale_start=*/1,
                      options, landmarks, world_T_base_refined, summary, map_hook);
}

Status BundleAdjust(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                    const std::vector<Pose3>& world_T_base_start, double odometry_scale_start,
                    const BundleAdjustmentOptions& options, Landmarks* landmarks,
                    std::vector<Pose3>* world_T_base_refined, BundleAdjustmentSummary* summary,
                    const MapHook& map_hook) {
  CHECK(landmarks != nullptr);
  CHECK(world_T_base_refined != nullptr);
  CHECK(summary != nullptr);
  const auto start = std::chrono::steady_clock::now();
  *summary = BundleAdjustmentSummary();
  SFM_RETURN_IF_ERROR(options.Check());
  SFM_RETURN_IF_ERROR(CheckInput(calibration, world_T_base_odometry, *landmarks));
  if (world_T_base_start.size() != world_T_base_odometry.size()) {
    return Status::Error("bundle adjustment: " + std::to_string(world_T_base_start.size()) +
                         " start poses for " + std::to_string(world_T_base_odometry.size()) +
                         " odometry poses");
  }
  if (&world_T_base_start != &world_T_base_odometry) {
    for (size_t f = 0; f < world_T_base_start.size(); ++f) {
      const Pose3& pose = world_T_base_start[f];
      if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite() ||
          !(pose.rotation.norm() > 0)) {
        return Status::Error("bundle adjustment: start pose " + std::to_string(f) +
                             " is not a finite rigid transform");
      }
    }
    // The first pose is the gauge (SPEC section 3): it stays the odometry's.
    const Pose3& first = world_T_base_odometry[0];
    const Pose3& first_start = world_T_base_start[0];
    if (!((first_start.translation - first.translation).norm() <= 1e-9 * (1 + first.translation.norm()) &&
          first_start.rotation.angularDistance(first.rotation) <= 1e-9)) {
      return Status::Error(
          "bundle adjustment: the first start pose must be the first odometry pose (the gauge)");
    }
  }
  if (!(odometry_scale_start > 0 && std::isfinite(odometry_scale_start))) {
    return Status::Error("bundle adjustment: the start odometry scale must be finite and > 0");
  }
  BundleAdjuster adjuster(calibration, world_T_base_odometry, world_T_base_start, odometry_scale_start,
                          options, landmarks, summary);
  const Status status = adjuster.Run(map_hook);
  summary->odometry_rotation_bias_estimated = adjuster.EstimatesRotationBias();
  if (summary->odometry_rotation_bias_estimated) {
    const std::array<double, 3>& b = summary->odometry_rotation_bias_rad;
    LOG(INFO) << "bundle adjustment: odometry rotation bias per step (" << b[0] << ", " << b[1] << ", "
              << b[2] << ") rad, angle-axis in the base frame";
  }
  *world_T_base_refined = adjuster.RefinedPoses();
  summary->time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return status;
}

}  // namespace sfm

#include "backend/bundle_adjustment/floor_prior_state.h"

#include <cmath>
#include <optional>

namespace sfm {

bool EstimatesRotationBias(const BundleAdjustmentOptions& options, const Pose3& base_T_camera,
                           const std::vector<Pose3>& world_T_base_odometry) {
  if (options.estimate_odometry_rotation_bias) return true;
  return options.estimate_odometry_rotation_bias_on_floor && options.floor_prior != FloorPriorMode::kOff &&
         FloorPriorRigProblem(base_T_camera, world_T_base_odometry, options.floor_sigma_m).empty();
}

void FloorPriorState::Select(bool first, const AdjustmentParameters& parameters, const Landmarks& landmarks,
                             BundleAdjustmentSummary* summary) {
  const BundleAdjustmentOptions& options = setup_.options;
  if (options.floor_prior == FloorPriorMode::kOff) {
    if (first) summary->floor_prior_report = "floor prior off (--floor_prior=off)";
    return;
  }
  if (first) selected_ = true;
  if (!first && !scale_free_) return;  // not applied in the first place
  const bool automatic = options.floor_prior == FloorPriorMode::kAuto;
  const double sigma_m = options.floor_sigma_m;
  const double camera_height_m = setup_.base_T_camera.translation.z();
  auto skip = [&](const std::string& why) {
    summary->floor_prior_report = first ? "floor prior not applied: " + why
                                        : "floor prior dropped after the outlier round, the odometry scale " +
                                              std::to_string(parameters.odometry_scale) +
                                              " it gave kept: " + why;
    floor_.points.clear();
    floor_.lines.clear();
  };
  if (first) {
    const std::string rig_problem = FloorPriorRigProblem(setup_.base_T_camera, setup_.odometry, sigma_m);
    // Even when forced on, a floor must be below the camera.
    if (!rig_problem.empty() && (automatic || !(camera_height_m > 0))) return skip(rig_problem);
    // The base poses are held on the floor (z with the floor sigma, tilt with floor sigma / camera
    // height) only where the odometry shows them there.
    base_on_floor_ = rig_problem.empty();
  }
  double camera_z_m = 0;
  for (const PoseParameters& pose : parameters.poses) {
    camera_z_m += (pose.ToPose() * setup_.base_T_camera).translation.z();
  }
  camera_z_m /= parameters.poses.size();
  const double half_width_m = 3 * sigma_m;
  // After the first selection the prior has pulled the floor it chose to z = 0: look for it
  // there, not again from below (stray landmarks under the floor may then gather in a slab).
  FloorPlane plane = FindFloorPlane(landmarks, camera_z_m, half_width_m, options.floor_min_landmarks,
                                    first ? std::nullopt : std::optional<double>(0.0));
  if (!plane.found) return skip(plane.why);
  const double allowed_m = AllowedFloorHeight();
  if (automatic && plane.z_m < -allowed_m) {
    // Mis-triangulated landmarks under the floor can gather in a slab, but not outnumber the
    // floor: a plane where the noise model allows it, holding more, is the floor.
    const FloorPlane allowed = FindFloorPlane(landmarks, camera_z_m, half_width_m,
                                              options.floor_min_landmarks, std::nullopt, -allowed_m);
    if (allowed.found && std::abs(allowed.z_m) <= allowed_m && allowed.support > plane.support) {
      stray_slab_note_ = "; a slab of " + std::to_string(plane.support) +
                         " landmarks at z = " + std::to_string(plane.z_m) + " m below it taken for stray";
      plane = allowed;
    }
  }
  if (first) {
    summary->floor_plane_z_m = plane.z_m;
    first_plane_z_m_ = plane.z_m;
  }
  if (automatic && !(std::abs(plane.z_m) <= allowed_m)) {
    return skip("the lowest horizontal plane (" + std::to_string(plane.support) + " landmarks) is at z = " +
                std::to_string(plane.z_m) + " m, beyond the " + std::to_string(allowed_m) +
                " m the odometry's scale sigma allows: the base origin is not on the floor");
  }
  floor_ = SelectFloorLandmarks(landmarks, plane.z_m, half_width_m);
  anchors_.clear();
  for (int line : floor_.lines) anchors_.push_back({landmarks.lines[line].end0, landmarks.lines[line].end1});
  scale_free_ = true;
  summary->floor_prior_report =
      "floor prior: plane at z = " + std::to_string(plane.z_m) + " m (" + std::to_string(plane.support) +
      " of " + std::to_string(plane.below_camera) + " landmarks below the cameras), " +
      std::to_string(floor_.points.size()) + " points and " + std::to_string(floor_.lines.size()) +
      " lines held" + (base_on_floor_ ? ", base poses held on it" : "") + stray_slab_note_ + start_note_;
}

bool FloorPriorState::bases_level_before_selection() const { return !selected_ && StartsAtFloorScale(); }

bool FloorPriorState::StartsAtFloorScale() const {
  const BundleAdjustmentOptions& options = setup_.options;
  return static_cast<int>(setup_.odometry.size()) >= options.floor_start_min_frames &&
         options.floor_prior != FloorPriorMode::kOff &&
         FloorPriorRigProblem(setup_.base_T_camera, setup_.odometry, options.floor_sigma_m).empty();
}

// A map s times too long, scaled about the first camera (height c above the floor, held by the
// bases' prior), has its floor at z = c (1 - s): the gain 1 / s = c / (c - z) puts it back at 0.
double FloorPriorState::StartGain(const AdjustmentParameters& parameters) const {
  if (!StartsAtFloorScale() || !scale_free_ || !(std::abs(first_plane_z_m_) <= AllowedFloorHeight())) {
    return 1;
  }
  const double camera_z_m = (parameters.poses[0].ToPose() * setup_.base_T_camera).translation.z();
  if (!(camera_z_m > first_plane_z_m_)) return 1;
  return camera_z_m / (camera_z_m - first_plane_z_m_);
}

void FloorPriorState::NoteStartScale(double odometry_scale, BundleAdjustmentSummary* summary) {
  start_note_ = "; started at odometry scale " + std::to_string(odometry_scale);
  summary->floor_prior_report += start_note_;
}

double FloorPriorState::AllowedFloorHeight() const {
  return 3 * setup_.noise.translation_sigma * setup_.base_T_camera.translation.z() +
         3 * setup_.options.floor_sigma_m;
}

void FloorPriorState::ScaleAnchorsAbout(const Eigen::Vector3d& centre, double gain) {
  for (auto& anchors : anchors_) {
    for (Eigen::Vector3d& anchor : anchors) anchor = centre + gain * (anchor - centre);
  }
}

void FloorPriorState::Clear() {
  floor_.points.clear();
  floor_.lines.clear();
}

void FloorPriorState::Summarise(BundleAdjustmentSummary* summary) const {
  summary->floor_prior_used = scale_free_ && holds_landmarks();
  summary->floor_points = static_cast<int>(floor_.points.size());
  summary->floor_lines = static_cast<int>(floor_.lines.size());
  summary->floor_point_indices = floor_.points;
  summary->floor_line_indices = floor_.lines;
}

}  // namespace sfm

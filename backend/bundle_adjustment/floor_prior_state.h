// The floor prior's state through one bundle adjustment (docs/bundle_adjustment.md, "Floor
// prior"): whether it applies (the odometry's scale factor is then free), the landmarks it holds,
// the anchors of its lines, and what its report says. The rules it applies are floor_prior.h's;
// the residuals floor_prior_cost.h's.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "backend/bundle_adjustment/adjustment_state.h"
#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/bundle_adjustment/floor_prior.h"
#include "backend/triangulation/landmarks.h"

namespace sfm {

// Whether the odometry's rotation bias is in the problem: asked for, or (auto) wherever the floor
// prior may apply, decided on the rig and the odometry before any solve (docs/bundle_adjustment.md,
// "Floor scale bias").
bool EstimatesRotationBias(const BundleAdjustmentOptions& options, const Pose3& base_T_camera,
                           const std::vector<Pose3>& world_T_base_odometry);

class FloorPriorState {
 public:
  using Anchors = std::vector<std::array<Eigen::Vector3d, 2>>;

  explicit FloorPriorState(const AdjustmentSetup& setup) : setup_(setup) {}

  // The decision and the selection. `first`: on the coarse map, where the rig and the odometry are
  // checked and the plane's height must agree with the odometry's noise model (auto); later, on
  // the map the prior has rescaled, the landmarks are selected again about the plane found there
  // (the removals renumber them). Writes the report (and, first, the plane's height) to `summary`.
  void Select(bool first, const AdjustmentParameters& parameters, const Landmarks& landmarks,
              BundleAdjustmentSummary* summary);

  // The prior applies: the odometry's scale factor is free and the selected landmarks held.
  bool applied() const { return scale_free_; }
  bool holds_landmarks() const { return !(floor_.points.empty() && floor_.lines.empty()); }
  // BaseOnFloorCost on every pose but the first (the odometry shows the rig on the floor).
  bool base_on_floor() const { return base_on_floor_; }
  // Before the first selection, where StartsAtFloorScale: the coarse solve holds the bases on the
  // floor.
  bool bases_level_before_selection() const;
  // At least options.floor_start_min_frames frames, the prior not off, and the odometry shows the
  // rig on a level floor (check 1 of docs/bundle_adjustment.md, "Floor prior").
  bool StartsAtFloorScale() const;
  // After the first selection, on the coarse map (bases held level, at the odometry's scale): the
  // gain about the first camera that puts the plane found at z = 0, the start the floor's scale
  // implies; 1 when the prior does not apply, not StartsAtFloorScale, or the plane is beyond what
  // the noise model allows (--floor_prior=on).
  double StartGain(const AdjustmentParameters& parameters) const;
  // The report notes the odometry scale the map was started at.
  void NoteStartScale(double odometry_scale, BundleAdjustmentSummary* summary);
  const FloorLandmarks& landmarks() const { return floor_; }
  // Each selected line's end-points when it was selected, the plane its prior holds it to.
  const Anchors& anchors() const { return anchors_; }
  void set_anchors(const Anchors& anchors) { anchors_ = anchors; }
  void ScaleAnchorsAbout(const Eigen::Vector3d& centre, double gain);
  // No landmark held any more (the map reverted to the odometry).
  void Clear();
  // The floor fields of `summary` (used, counts, indices).
  void Summarise(BundleAdjustmentSummary* summary) const;

 private:
  // How far from z = 0 the floor of a map at the odometry's scale may be: a map whose trajectory is
  // s times too long has its floor at (1 - s) * camera height (the map scaled about the cameras,
  // which the rig holds at their height); the noise model allows |s - 1| up to 3 translation
  // sigmas, and the slab's half width (3 floor sigmas) is the plane's own resolution.
  double AllowedFloorHeight() const;

  const AdjustmentSetup& setup_;
  bool scale_free_ = false;
  bool selected_ = false;       // the first selection was made
  double first_plane_z_m_ = 0;  // m, the plane it found
  bool base_on_floor_ = false;
  std::string stray_slab_note_;  // the report's note when the first selection passed over a stray slab
  std::string start_note_;       // the report's note of the scale the fine solves started at
  FloorLandmarks floor_;
  Anchors anchors_;
};

}  // namespace sfm

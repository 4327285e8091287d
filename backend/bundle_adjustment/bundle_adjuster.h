// Bundle adjustment of the robot trajectory and the landmarks, with the wheel odometry as a prior.
//
// Minimises, over the poses world_T_base of every frame but the first (the gauge: SPEC section 3
// keeps the first odometry pose where it is), the 3D points and the 3D lines (orthonormal
// representation, Bartoli & Sturm 2005):
//   sum rho(|point reprojection error|^2) + sum rho(|end-point-to-line distances|^2)
//   + sum |whitened odometry relative-pose error|^2
// with rho a robust loss on the image terms (pixels). It solves in stages - poses and points at a
// coarse loss scale, each line alone, everything at the fine scale - then removes the
// observations whose error exceeds a threshold, and the landmarks left with fewer than two views,
// and solves again. Details, units and measured figures: docs/bundle_adjustment.md.
//
// The parts: problem_builder.h (the Ceres problems), landmark_filter.h (the removals),
// floor_prior_state.h (the floor prior's decision and selection); here the schedule of solves and
// removals, as steps a caller runs in order (COLMAP's IterativeGlobalRefinement runs adjustment,
// track completion and filtering the same way: the pipeline extends the tracks between them).
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "backend/bundle_adjustment/adjustment_state.h"
#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/bundle_adjustment/floor_prior_state.h"
#include "backend/bundle_adjustment/landmark_filter.h"
#include "backend/triangulation/reconstruction.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

// One adjustment of `reconstruction` (its calibration, poses and landmarks; the junctions and
// tracks are not read). The solves start from reconstruction->world_T_base and from the
// odometry's scale factor `odometry_scale_start` (the odometry and 1, or e.g. a vision-first
// trajectory, or an earlier adjustment's refined poses and summary.odometry_scale); the odometry
// world_T_base_odometry stays the prior's measurement and the scale prior stays at 1. A start
// scale other than 1 is held in the odometry priors until the floor prior frees it (without a
// floor it stays). Uses calibration.camera's K (observations are undistorted pixels),
// base_T_camera and odometry_noise (translation sigma as a fraction of the distance travelled
// between consecutive frames, floored at options.odometry_min_distance_m; rotation sigma per
// frame).
//
// The steps, in order (each does nothing once the adjustment has finished early):
//   Start          checks the input; removes, and counts in `summary`, the observations that
//                  cannot be evaluated at the start poses (a point behind the camera, a line
//                  through the camera centre), the landmarks with fewer than two views and those
//                  whose position the views do not determine (triangulation angle below the
//                  options' minimum; for a line, parallel to the motion or in an epipolar plane).
//   SolveCoarse    poses and points at the coarse loss scale, each line alone, the removals on
//                  the refined poses, the floor prior's decision.
//   SolveFine      everything at the fine loss scale.
//   AcceptChangedMap   optional: after the caller changed reconstruction->landmarks (the track
//                  extension: observations added, landmarks merged or dropped, point_landmark
//                  indices kept valid), the removals again, before the outlier rounds judge the
//                  new observations as the old ones.
//   Filter         the outlier rounds (observations beyond outlier_threshold_px removed, solved
//                  again), the observability rounds (landmarks the last solve made unobservable
//                  dropped, solved again), the floor scale's line search.
//   Finish         the summary's figures; reconstruction->world_T_base the refined poses.
// After every step reconstruction->world_T_base holds the current poses. Refined lines get point
// and direction from the solution, end0 at their junction point (point_landmark) when they have
// one, otherwise end0 and end1 projected onto the refined line; point_landmark indices are
// renumbered after removals (-1 when the point was removed).
//
// With nothing left to solve (no frame pair, or no landmark, from the start or after the
// removals) the adjustment finishes early, the trajectory the odometry and the status OK;
// summary.solver_report says why. Errors: bad options, inconsistent input (an observation of a
// frame that does not exist, a non-positive noise sigma, K not positive, start poses not as many
// as the odometry's or the first not the odometry's, a start scale not > 0), or Ceres failing;
// the outputs are then unspecified.
//
// Not copyable; `world_T_base_odometry`, `options`, `reconstruction` and `summary` must outlive it.
// Keep it on the stack: Ceres orders the blocks of the poses' ordering group by address, and the
// odometry's scale factor and rotation bias (members) then come after the poses (heap), the order
// the results were measured with.
class BundleAdjustment {
 public:
  BundleAdjustment(const std::vector<Pose3>& world_T_base_odometry, double odometry_scale_start,
                   const BundleAdjustmentOptions& options, Reconstruction* reconstruction,
                   BundleAdjustmentSummary* summary);
  BundleAdjustment(const BundleAdjustment&) = delete;
  BundleAdjustment& operator=(const BundleAdjustment&) = delete;

  Status Start();
  Status SolveCoarse();
  Status SolveFine();
  Status AcceptChangedMap();
  Status Filter();
  void Finish();

  // Nothing (more) to solve, or Start failed: the later steps do nothing.
  bool finished() const { return state_ != State::kRunning; }

  // Called after each iteration of each joint solve with the solve's number (1-based) and the
  // iteration's, for a progress display; it must not change anything the solve reads.
  using IterationHook = std::function<void(int solve, int iteration)>;
  void SetIterationHook(IterationHook hook) { iteration_hook_ = std::move(hook); }

 private:
  enum class State { kNotStarted, kRunning, kNothingToSolve, kReverted };

  Status CheckStart() const;
  // Poses, points and (with_lines) lines together, until Ceres's function_tolerance; the two-view
  // lines left out are then solved alone on the solve's poses.
  Status Solve(double loss_scale_px, bool with_lines, double function_tolerance);
  // With no landmark left, the poses they gave are no better than the odometry's.
  void RevertToOdometry(const std::string& why);
  void ScaleMapAboutFirstCamera(double gain);
  Status SearchScale();
  void FinishFloorSummary();
  void WritePoses() { reconstruction_->world_T_base = parameters_.Poses(); }

  const std::chrono::steady_clock::time_point start_time_;
  const double odometry_scale_start_;
  Reconstruction* const reconstruction_;
  Landmarks* const landmarks_;
  BundleAdjustmentSummary* const summary_;
  const AdjustmentSetup setup_;
  AdjustmentParameters parameters_;
  FloorPriorState floor_;
  LandmarkFilter filter_;
  State state_ = State::kNotStarted;
  // The first fine solve stopped at the intermediate tolerance (an outlier round follows it).
  bool loose_ = false;
  IterationHook iteration_hook_;
};

// All the steps without a change of the map.
Status BundleAdjust(const std::vector<Pose3>& world_T_base_odometry, double odometry_scale_start,
                    const BundleAdjustmentOptions& options, Reconstruction* reconstruction,
                    BundleAdjustmentSummary* summary);

}  // namespace sfm

// Bundle adjustment of the robot trajectory and the landmarks, starting from the wheel odometry.
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
#pragma once

#include <functional>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

// Refines `landmarks` in place and writes the refined world_T_base of every frame to
// `world_T_base_refined` (same length as the odometry).
//
// Uses calibration.camera's K (observations are undistorted pixels), calibration.base_T_camera
// and calibration.odometry_noise (translation sigma as a fraction of the distance travelled
// between consecutive frames, floored at options.odometry_min_distance_m; rotation sigma per frame).
//
// Before solving it removes, and counts in `summary`: observations that cannot be evaluated at the
// odometry poses (a point behind the camera, a line through the camera centre), landmarks with
// fewer than two views, and landmarks whose position the views do not determine (triangulation
// angle below the options' minimum; for a line, parallel to the motion or in an epipolar plane).
// The last check is repeated on the refined poses before the joint solve and in every outlier round.
// Refined lines get point and direction from the solution, end0 at their junction point
// (point_landmark) when they have one, otherwise end0 and end1 projected onto the refined line;
// point_landmark indices are renumbered after removals (-1 when the point was removed).
//
// With nothing left to solve (no frame pair, or no landmark, from the start or after the
// removals) the refined trajectory is the odometry and the status OK; summary.solver_report says why. Errors:
// bad options, inconsistent input (an observation of a frame that does not exist, a non-positive noise sigma,
// K not positive), or Ceres failing; the outputs are then unspecified.
//
// `map_hook` (optional): called once with the poses world_T_base of that moment and the landmarks,
// which it may change (observations added, landmarks merged or dropped; point_landmark indices
// kept valid): the pipeline's track extension (docs/tracks_and_triangulation.md, "Track
// extension"). kAfterCoarse: after the coarse stage, before the floor prior is decided and the fine
// solves; the landmarks then pass the removals of the coarse stage. kAfterFine: after the first fine
// solve, before its outlier rounds, which then judge the new observations as the old ones (beyond
// outlier_threshold_px removed) and whose solves refine the changed map with the poses (with no
// outlier round, one fine solve more).
struct MapHook {
  enum When { kAfterCoarse, kAfterFine };
  When when = kAfterFine;
  std::function<void(const std::vector<Pose3>& world_T_base, Landmarks* landmarks)> change;
};
Status BundleAdjust(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                    const BundleAdjustmentOptions& options, Landmarks* landmarks,
                    std::vector<Pose3>* world_T_base_refined, BundleAdjustmentSummary* summary,
                    const MapHook& map_hook = MapHook());

// The same, the solves starting from `world_T_base_start` and the odometry's scale factor from
// `odometry_scale_start` (e.g. an earlier adjustment's refined poses and summary.odometry_scale)
// instead of the odometry and 1; the odometry stays the prior's measurement, and the scale prior
// stays at 1. A start scale other than 1 is held in the odometry priors until the floor prior
// frees it (without a floor it stays). The start poses: as many as the odometry's, the first the
// odometry's (the gauge); the scale > 0; else an error.
Status BundleAdjust(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                    const std::vector<Pose3>& world_T_base_start, double odometry_scale_start,
                    const BundleAdjustmentOptions& options, Landmarks* landmarks,
                    std::vector<Pose3>* world_T_base_refined, BundleAdjustmentSummary* summary,
                    const MapHook& map_hook = MapHook());

// Refines `landmarks` in place on the poses world_T_base, which are held: each point and each line
// alone at the fine loss scale, then the outlier rounds of BundleAdjust (observations beyond
// options.outlier_threshold_px removed, landmarks left with fewer than two views or unobservable on
// these poses dropped, solved again), ending, as BundleAdjust does, with no observation beyond the
// threshold. No odometry or floor prior (the poses are not solved for). `summary` counts as
// BundleAdjust's (solves and iterations stay 0: no pose was solved). For landmarks triangulated on
// an adjustment's refined poses (docs/tracks_and_triangulation.md, "Re-triangulation on the
// refined poses"). Errors as BundleAdjust's.
Status RefineLandmarksOnFixedPoses(const Calibration& calibration, const std::vector<Pose3>& world_T_base,
                                   const BundleAdjustmentOptions& options, Landmarks* landmarks,
                                   BundleAdjustmentSummary* summary);

}  // namespace sfm

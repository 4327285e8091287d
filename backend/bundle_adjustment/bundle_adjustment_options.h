// Options and summary of the bundle adjustment (bundle_adjuster.h). Defaults and how they were
// chosen: docs/bundle_adjustment.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "backend/triangulation/triangulation_options.h"
#include "util/status.h"

namespace sfm {

enum class RobustLoss { kHuber, kCauchy };

// The ground-plane (floor) prior (docs/bundle_adjustment.md, "Floor prior"): off; auto (when the
// rig, the odometry and the first solve's map show a ground robot whose base origin is on the
// floor); on (whenever a floor plane is found, without the checks of the rig, the odometry and
// the plane's height).
enum class FloorPriorMode { kOff, kAuto, kOn };

enum class BundleAdjustmentLinearSolver {
  // DENSE_SCHUR up to dense_schur_max_frames frames; above, SPARSE_SCHUR, or ITERATIVE_SCHUR when
  // the reduced system has more than iterative_schur_min_cells_per_frame cells per frame
  kAuto,
  kDenseSchur,      // ceres::DENSE_SCHUR
  kSparseSchur,     // ceres::SPARSE_SCHUR (SuiteSparse or Eigen sparse, whichever Ceres has)
  kIterativeSchur,  // ceres::ITERATIVE_SCHUR, SCHUR_JACOBI preconditioner
};

struct BundleAdjustmentOptions {
  RobustLoss robust_loss = RobustLoss::kHuber;  // on the image residuals only
  double robust_loss_scale_px = 1.0;            // px, where the loss leaves the quadratic
  // px, the loss scale of the first solves from the odometry, where errors of tens of pixels are
  // drift, not outliers; observations beyond it are removed after them.
  double coarse_loss_scale_px = 20.0;
  int max_iterations = 100;           // per Ceres solve
  // Ceres's function_tolerance (relative cost change that ends a solve) of the solve whose result
  // is returned; Ceres's default.
  double function_tolerance = 1e-6;
  // The same for a joint solve that an outlier round follows: its result is only the start of
  // the next solve. A run whose last solve was loose (the outlier round removed nothing) solves
  // once more at function_tolerance.
  double intermediate_function_tolerance = 1e-4;
  double outlier_threshold_px = 3.0;  // px, an observation's error (norm of its 2 residuals)
  int outlier_rounds = 1;             // remove-outliers-and-solve-again rounds after the joint solve
  BundleAdjustmentLinearSolver linear_solver = BundleAdjustmentLinearSolver::kAuto;
  int dense_schur_max_frames = 100;  // frames, kAuto's switch to SPARSE_SCHUR
  // kAuto's switch to ITERATIVE_SCHUR: the reduced (pose) system's cells, the frame pairs i <= j
  // that share a landmark, per frame (docs/bundle_adjustment.md, "Solver").
  double iterative_schur_min_cells_per_frame = 120;
  // m, floor on the distance travelled between two frames when the odometry prior's translation
  // sigmas are set from the distance (a robot turning in place still slips); a step shorter than
  // this is weighted the same in every direction (its measured direction is mostly slip).
  double odometry_min_distance_m = 0.05;
  // Estimate the odometry's constant rotation increment per step b jointly with the poses (one
  // shared 3-vector, zero-mean Gaussian prior with the noise model's per-frame rotation sigma;
  // docs/bundle_adjustment.md, "Odometry rotation bias").
  bool estimate_odometry_rotation_bias = false;
  // Estimate it also (auto) where the floor prior may apply: the floor prior not off and the rig
  // and odometry of a ground robot (FloorPriorRigProblem empty). The floor prior's free scale
  // factor makes the map's horizontal scale soft, and the yaw drift a constant heading error
  // leaves is paid for by sideways shifts of the cameras, radial on a loop: the floor scale then
  // reads the trajectory too long (docs/bundle_adjustment.md, "Floor scale bias").
  bool estimate_odometry_rotation_bias_on_floor = true;
  double min_point_triangulation_angle_deg = 1.0;  // deg, points with less are dropped before solving
  double min_line_triangulation_angle_deg = 2.0;   // deg, lines with less are dropped (unobservable)
  // m, a point less deep than this in a camera that observes it, or a line whose points seen at
  // an observation's p0 or p1 are (ObservedLineDepth), is dropped as unobservable, on the refined
  // poses and landmarks (not before the first solve, see DropUnobservableLandmarks). A landmark of
  // a view pair without baseline is intersected next to the camera centre, where the triangulation
  // angles above see any baseline as large.
  double min_depth_m = kMinDepthM;
  FloorPriorMode floor_prior = FloorPriorMode::kAuto;
  // m, sigma of a floor landmark's world z about 0: how far a junction the floor prior selects
  // may be from the plane of the base origin (floor flatness, wheels sinking in), also the unit
  // of every floor threshold (docs/bundle_adjustment.md, "Floor prior").
  double floor_sigma_m = 0.01;
  // Landmarks a floor plane needs at least (besides being a peak of the height distribution).
  int floor_min_landmarks = 10;
  // frames; from this many on, the coarse solve holds the bases on the floor and the fine solves
  // start at the scale its floor gives (docs/bundle_adjustment.md, "Floor prior"): on long
  // corridors they otherwise crawl along the scale (960 frames: 101 iterations). Below, the
  // robustness benchmark's 60-frame runs lost with it (ATE worse on 32 of 72, better on 24).
  int floor_start_min_frames = 400;

  // An error naming the first bad field, or OK.
  Status Check() const;
};

struct BundleAdjustmentSummary {
  int frames = 0;
  int points = 0;        // point landmarks after the removals before the first solve
  int lines = 0;         // line landmarks after the removals before the first solve
  int observations = 0;  // point and line observations then
  // Ceres solves of the poses (0 when nothing was left to solve) and their iterations; the
  // per-line solves on fixed poses are not counted.
  int solves = 0;
  int iterations = 0;
  double initial_cost = 0;  // Ceres cost (1/2 sum of robustified squares) before the first solve
  double final_cost = 0;    // after the last solve (fine loss scale, the observations left then)
  bool converged = false;   // every counted solve ended by a convergence test, not max_iterations
  // Observations removed before solving: a point behind the camera, a line through its centre.
  int observations_unusable = 0;
  // Outliers removed: error above the coarse scale after the coarse solves, above
  // outlier_threshold_px after a joint one.
  int observations_removed = 0;
  int points_removed = 0;  // left with fewer than 2 views
  int lines_removed = 0;   // left with fewer than 2 views
  // Dropped with a triangulation angle below the minimum (before solving, or on refined poses).
  int points_unobservable = 0;
  int lines_unobservable = 0;
  // Of those, dropped after the last joint solve (at most three rounds, the problem solved again
  // after each; docs/bundle_adjustment.md, "Robust loss, stages and outliers"), and those solves.
  int landmarks_unobservable_after_last_solve = 0;
  int observability_solves = 0;
  double point_rms_px = 0;    // RMS reprojection error of the point observations kept, at the end
  double line_rms_px = 0;     // RMS end-point-to-line distance of the line observations kept
  // Floor prior: used in the last solve or not, the landmarks it held there, the floor's height
  // when it was first found (before the prior moved it), the odometry's scale factor (1 without
  // the prior), and what was decided and why (logged by the pipeline).
  bool floor_prior_used = false;
  int floor_points = 0;
  int floor_lines = 0;
  std::optional<double> floor_plane_z_m;  // m; none when no floor plane was found
  double odometry_scale = 1;
  std::string floor_prior_report;
  // The landmarks it held in the last solve: indices into the returned landmarks.
  std::vector<int> floor_point_indices, floor_line_indices;
  // rad per step, angle-axis in the base frame: the odometry's estimated rotation bias b (zero
  // when options.estimate_odometry_rotation_bias is off or nothing was solved).
  std::array<double, 3> odometry_rotation_bias_rad = {0, 0, 0};
  bool odometry_rotation_bias_estimated = false;  // b was in the problem (on, or auto on a ground robot)
  double time_s = 0;          // wall-clock seconds, the whole call
  std::string solver_report;  // Ceres's BriefReport of the last solve, or why nothing was solved
};

}  // namespace sfm

// Drift of an estimated camera trajectory against ground truth: absolute trajectory error (ATE)
// and relative pose error (RPE) as defined by Sturm et al., "A Benchmark for the Evaluation of
// RGB-D SLAM Systems", IROS 2012. Definitions and units: docs/metrics.md.
#pragma once

#include <vector>

#include "geometry/pose.h"

namespace sfm {

// All three are RMSEs over the frames (ATE) or consecutive frame pairs (RPE). A figure that is not
// defined for the input (ATE with no frame, RPE with fewer than two) is NaN, which
// JsonNumber writes as the `null` that SPEC section 3 asks for.
struct DriftMetrics {
  double ate_m = 0;        // metres, camera positions after AlignSE3
  double rpe_trans_m = 0;  // metres per frame
  double rpe_rot_rad = 0;  // radians per frame
  // The shape without the scale (which one camera cannot observe): camera positions after AlignSim3,
  // and that similarity's scale (> 1: the estimate is too short). docs/metrics.md.
  double ate_sim3_m = 0;
  double sim3_scale = 1;
};

// Sturm et al.'s ATE: the RMSE over frames of |truth_i - T * estimated_i| (camera positions, metres),
// T = AlignSE3 of the estimated positions onto the true ones (rigid, no scale; translation-only
// when degenerate). Both vectors hold world_T_camera per frame, same length (CHECKed).
double AbsoluteTrajectoryError(const std::vector<Pose3>& world_T_camera_estimated,
                               const std::vector<Pose3>& world_T_camera_truth);

// The ATE after the best similarity (AlignSim3) instead of a rigid transform, and its scale: the
// trajectory's shape error and its length error apart. Same inputs; NaN for both with no frame.
struct SimilarityTrajectoryError {
  double ate_m = 0;
  double scale = 1;
};
SimilarityTrajectoryError AbsoluteTrajectoryErrorSim3(const std::vector<Pose3>& world_T_camera_estimated,
                                                      const std::vector<Pose3>& world_T_camera_truth);

struct RelativePoseError {
  double trans_m = 0;  // RMSE of |translation of E_i|, metres
  double rot_rad = 0;  // RMSE of the rotation angle of E_i, radians
};

// Sturm et al.'s RPE with a step of delta = 1 frame, its translation and rotation parts:
// E_i = (truth_i^-1 truth_{i+1})^-1 (est_i^-1 est_{i+1}) for i = 0..n-2, i.e. the error of the
// motion from frame i to i+1 expressed in camera i+1. It needs no alignment: a rigid change of
// either world frame cancels. Same inputs as AbsoluteTrajectoryError.
RelativePoseError ComputeRelativePoseError(const std::vector<Pose3>& world_T_camera_estimated,
                                           const std::vector<Pose3>& world_T_camera_truth);

// ATE, RPE and the Sim(3) ATE together (the `ate_*` and `rpe_*` figures of metrics.json).
DriftMetrics ComputeDrift(const std::vector<Pose3>& world_T_camera_estimated,
                          const std::vector<Pose3>& world_T_camera_truth);

}  // namespace sfm

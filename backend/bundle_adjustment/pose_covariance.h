// The refined poses' own uncertainty: the first-order covariance of bundle adjustment's poses,
// (J^T J)^-1 restricted to the poses (the landmarks marginalised by their Schur complement), with
// the first pose fixed as in BundleAdjust (the gauge). The wireframe selection uses it in place of
// a fixed random-walk model of the pose error (PoseDrift, landmark_uncertainty.h);
// docs/tracks_and_triangulation.md, "Pose error from bundle adjustment". The result type,
// PoseCovariance, is in landmark_uncertainty.h (its user).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/bundle_adjustment/bundle_adjustment_options.h"
#include "backend/triangulation/landmark_uncertainty.h"
#include "backend/triangulation/landmarks.h"
#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

// The covariance of the refined poses world_T_base_refined given the final `landmarks` (their
// observations after bundle adjustment's outlier removal) and the odometry priors as BundleAdjust
// weighs them (OdometryStepSigmasFor, calibration.odometry_noise): image residuals divided by
// pixel_sigma_px, no robust loss (the inliers' weights are about 1), the floor prior and the
// odometry's scale factor left out (the scale taken as known). A landmark whose own information is
// singular (relative 1e-9) is left out (it fixes no pose). Errors: sizes that do not match, an
// observation of a missing frame, a non-positive sigma, or a reduced camera system that is not
// positive definite.
Status ComputePoseCovariance(const Calibration& calibration, const std::vector<Pose3>& world_T_base_odometry,
                             const std::vector<Pose3>& world_T_base_refined, const Landmarks& landmarks,
                             const BundleAdjustmentOptions& options, double pixel_sigma_px,
                             PoseCovariance* covariance);

// Is the covariance calibrated? For a lag of k frames, over every pair (f0, f0 + k): the RMS of
// the predicted relative errors, sqrt(mean trace) of PoseCovariance::Relative's rotation and
// centre blocks, against the RMS of the actual ones, the estimate's pose of camera f0 + k in camera
// f0's frame against the truth's (rotation angle; centre distance, metres). Lags with no pair are
// left out.
struct PoseCovarianceCheck {
  int lag = 0;
  int pairs = 0;
  double predicted_rotation_rad = 0, actual_rotation_rad = 0;
  double predicted_centre_m = 0, actual_centre_m = 0;
};
std::vector<PoseCovarianceCheck> CheckPoseCovariance(const PoseCovariance& covariance,
                                                     const std::vector<Pose3>& world_T_camera_estimate,
                                                     const std::vector<Pose3>& world_T_camera_truth,
                                                     const std::vector<int>& lags);

}  // namespace sfm

// Self-calibrating bundle adjustment of a data set's own measurements: one camera K shared by all
// views (fx, fy, cx, cy, zero skew, optionally one radial term k1), every pose and every 3D point
// free, minimising the robust reprojection error of the data set's matched image points. Used to
// give a sequence (which allows one K) a ground truth consistent with its images when the data
// set's own cameras each have their own K (VGG Corridor: docs/importers.md, "VGG").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct RefitObservation {
  int view = 0;                                     // index into the poses
  int point = 0;                                    // index into the points
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // measured, OpenCV pixel-centre convention
};

struct SharedCameraRefitOptions {
  // Which of K's parameters are estimated; the others keep their start values.
  bool refine_focal = true;            // fx, fy
  bool refine_principal_point = true;  // cx, cy
  // k1 of OpenCV's model (x_d = x (1 + k1 r^2), normalised coordinates): its start value, and
  // whether it is estimated (else held there, e.g. at a value known from a separate calibration).
  double k1 = 0;
  bool radial_k1 = false;
  // Huber loss scale, pixels. Corners that a data set's own cameras reproject to 0.28 px (median
  // distance, i.e. sigma ~0.24 px per axis for Gaussian errors) are trusted in full up to ~4 sigma;
  // beyond, mismatched or drifted corners pull linearly.
  double huber_px = 1.0;
  int max_iterations = 200;
};

struct SharedCameraRefit {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  // zero skew
  double k1 = 0;                                    // 0 unless options.radial_k1
  std::vector<Pose3> camera_T_world;                // in the reference centres' frame and units
  std::vector<Eigen::Vector3d> points;              // same frame
  // Reprojection error, pixels (distance, all observations, no outlier removed): median per view
  // and over all; the same for the start.
  std::vector<double> view_median_px;
  double median_px = 0, start_median_px = 0;
  // Per view: distance of the refit camera centre from its reference centre (after the gauge's
  // similarity, below), in the reference's units.
  std::vector<double> centre_offset;
  double gauge_scale = 1;  // scale of the similarity that moved the solution onto the reference centres
  int observations = 0;    // used in the solve
  int iterations = 0;
};

// Refits from the start values (K's skew is ignored). The gauge (7 dof: a similarity of the whole
// solution leaves every reprojection unchanged) is held during the solve by fixing pose 0 and the
// distance between the first and last camera centres; afterwards the whole solution is moved by
// the similarity that maps its camera centres onto `reference_centres` in least squares (Umeyama
// 1991), so that it lies in the reference's frame and units without being pinned to one camera.
// Fails on fewer than 2 views, sizes that disagree, an observation out of range, a view with fewer
// than 6 observations, first and last centres that coincide, or a point behind a camera at the start.
Status RefitSharedCamera(const Eigen::Matrix3d& start_K, const std::vector<Pose3>& start_camera_T_world,
                         const std::vector<Eigen::Vector3d>& start_points,
                         const std::vector<RefitObservation>& observations,
                         const std::vector<Eigen::Vector3d>& reference_centres,
                         const SharedCameraRefitOptions& options, SharedCameraRefit* result);

// Pixel of a point in the camera frame through K and k1 (zero skew), as the refit models it.
Eigen::Vector2d ProjectWithRadial(const Eigen::Matrix3d& K, double k1, const Eigen::Vector3d& point_camera);

}  // namespace sfm

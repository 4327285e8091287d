// The rules that remove observations and landmarks between the solves of a bundle adjustment
// (docs/bundle_adjustment.md, "Robust loss, stages and outliers" and "Unobservable landmarks"),
// judged on the current poses, and the counts they leave in the summary. COLMAP's FilterPoints
// in the shape of this problem: reprojection error, views, triangulation angle and depth.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "backend/bundle_adjustment/adjustment_state.h"
#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/triangulation/landmarks.h"

namespace sfm {

class LandmarkFilter {
 public:
  // `parameters` are read at each call (the poses then current); `landmarks` are changed in place;
  // the removals are counted in `summary`.
  LandmarkFilter(const AdjustmentSetup& setup, const AdjustmentParameters& parameters, Landmarks* landmarks,
                 BundleAdjustmentSummary* summary)
      : setup_(setup), parameters_(parameters), landmarks_(landmarks), summary_(summary) {}

  // The observations that cannot be evaluated at the current poses: a point behind the camera, a
  // line through its centre (summary.observations_unusable).
  void DropUnusableObservations();
  // The observations whose error (norm of the two residuals) exceeds threshold_px
  // (summary.observations_removed); returns how many.
  int RemoveOutliers(double threshold_px);
  // The landmarks left with fewer than two views (summary.points_removed, lines_removed).
  void RemoveLandmarksWithFewViews();
  // The landmarks whose position the views do not determine: triangulation angle below the
  // options' minimum (for a line also the angle of its back-projected planes), and with `refined`
  // (the landmarks and poses have been solved for) closer than min_depth_m to a camera that sees
  // them. Not before the first solve: landmarks triangulated on drifting odometry can start
  // within min_depth_m of a camera (or behind it) and be fine after it (the triangulation already
  // held them to the floor on the odometry's poses). Returns the number dropped
  // (summary.points_unobservable, lines_unobservable).
  int DropUnobservableLandmarks(bool refined);
  int CountObservations() const;
  // summary.point_rms_px and line_rms_px of the observations kept.
  void ComputeRms();

 private:
  // The residuals of one observation at the current parameters; false when it cannot be evaluated.
  // A point's are whitened by its sqrt_information as the solver sees them, or pixels (whitened
  // false: the RMS the summary reports).
  bool PointResiduals(const PointLandmark& point, const PointObservation& observation, Eigen::Vector2d* r,
                      bool whitened = true) const;
  bool LineResiduals(const OrthonormalLine& line, const LineObservation& observation,
                     Eigen::Vector2d* r) const;
  // Removes the landmarks that `keep_point` / `keep_line` reject, renumbering point_landmark.
  // Returns the numbers of points and lines removed.
  template <typename KeepPoint, typename KeepLine>
  std::pair<int, int> RemoveLandmarks(KeepPoint keep_point, KeepLine keep_line);
  template <typename Observations>
  std::vector<Pose3> CameraPoses(const Observations& observations) const;

  const AdjustmentSetup& setup_;
  const AdjustmentParameters& parameters_;
  Landmarks* landmarks_;
  BundleAdjustmentSummary* summary_;
};

}  // namespace sfm

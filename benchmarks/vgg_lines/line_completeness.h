// Completeness of a wireframe against ground-truth 3D line segments (issue 19, the VGG corridor's
// bt.l3d): the share of the true lines' length within a distance of a reconstructed edge.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace sfm {

struct LineCompleteness {
  double true_length = 0;    // summed length of the true segments
  double within_length = 0;  // of it, within the threshold of a reconstructed edge
  double Share() const { return true_length > 0 ? within_length / true_length : 0; }
};

// Each true segment is sampled every `step` (at least its two ends); a sample is within when its
// distance to the nearest reconstructed edge (segments between `vertices`) is at most
// `threshold`; each sample stands for its share of the segment's length.
LineCompleteness MeasureLineCompleteness(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& true_lines,
                                         const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<std::pair<int, int>>& edges, double threshold,
                                         double step);

// What the images give the reconstruction of true lines: a camera (K, camera_T_world as the
// rotation R and translation t of x = K (R X + t), the image size) and the 2D segments found in its
// image (undistorted pixels).
struct LineSupportView {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  int width = 0, height = 0;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;
};

struct LineImageSupport {
  double true_length = 0;
  double visible_length = 0;   // projects into at least min_views images (positive depth)
  double detected_length = 0;  // and lies within px of a 2D segment in at least min_views of them
};

// Each true segment sampled every `step` as MeasureLineCompleteness; a sample is visible in a view
// when it has positive depth and projects inside the image, detected there when its projection is
// within `px` pixels of one of the view's segments.
LineImageSupport MeasureLineImageSupport(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& true_lines,
                                         const std::vector<LineSupportView>& views, double px, double step,
                                         int min_views);

}  // namespace sfm

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

}  // namespace sfm

// Overlay images of detected segments and junctions (detect_junctions, benchmark_junctions).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "frontend/junctions/junction.h"
#include "frontend/segments/line_segment.h"

namespace sfm {

// Extra points to mark with hollow circles (for example true junctions that were missed) and extra
// segments to draw thin (for example ground-truth segments), with their colour (BGR) and a legend
// label.
struct OverlayMarks {
  std::vector<Eigen::Vector2d> points;
  LineSegments lines;
  cv::Scalar colour;
  std::string label;
};

// BGR colour of a junction type in overlays: L red, Y green, ARROW blue, T magenta, X yellow, N white.
cv::Scalar JunctionTypeColour(JunctionType type);

// The 8-bit grey (or BGR) image in grey, enlarged `scale` times (pixel centres stay pixel
// centres: x -> (x + 0.5) scale - 0.5), with the detected segments thin in cyan, each junction's
// segments drawn from its location to their end-points and a dot at its location, both in its type's
// colour, the marks' points as hollow circles and their lines thin, and a legend with the count of each type.
cv::Mat DrawJunctionOverlay(const cv::Mat& image, const LineSegments& segments, const Junctions& junctions,
                            int scale, const std::vector<OverlayMarks>& marks = {});

}  // namespace sfm

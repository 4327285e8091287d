// The plumb-line estimate of a camera's radial distortion (Brown 1971, "Close-range camera
// calibration"): edges that are straight in the world bow in a distorted image. For each long
// segment a data set gives (end points in the image), the image's edge is located across the chord
// at evenly spaced points, its bow (the 4t(1-t) coefficient of a fit along the chord) is measured,
// and k1 of OpenCV's model (x_d = x (1 + k1 r^2), normalised coordinates about the principal point)
// is the least-squares factor between the measured bows and the bows one unit of k1 predicts.
// Used by the VGG importer (--vgg_k1_from_lines; docs/importers.md, "VGG").
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "util/status.h"

namespace sfm {

struct PlumbLineSegment {
  int image = 0;                                                               // index into the images
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero(), p1 = Eigen::Vector2d::Zero();  // pixels
};

struct PlumbLineOptions {
  // Segments shorter than this are skipped: a bow grows with the square of the length, so short
  // edges carry little of it. Pixels.
  double min_length_px = 100;
  // An edge whose located points scatter about their fit by more than this (RMS) is not one clean
  // straight edge (a corner, a texture, two edges) and is skipped. Pixels.
  double max_fit_rms_px = 0.5;
};

struct PlumbLineEstimate {
  double k1 = 0;
  double k1_sigma = 0;  // from the scatter of the bows about the fit
  int edges = 0;        // segments used
};

// `images` are 8-bit grey; K gives the principal point and focal lengths (skew ignored). Fails
// when fewer than 3 segments qualify, or none of them would bow under a distortion.
Status EstimateRadialDistortionFromEdges(const std::vector<cv::Mat>& images,
                                         const std::vector<PlumbLineSegment>& segments,
                                         const Eigen::Matrix3d& K, const PlumbLineOptions& options,
                                         PlumbLineEstimate* estimate);

}  // namespace sfm

// Synthetic test images with known straight edges: filled convex polygons, blurred, with noise.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "frontend/segments/line_segment.h"

namespace sfm::testing {

struct Polygon {
  std::vector<Eigen::Vector2d> vertices;  // convex, pixels (origin at the centre of the top-left pixel)
  double grey = 180;                      // fill level
};

struct SyntheticImageOptions {
  int width = 256, height = 256;  // pixels
  double background = 60;         // grey level
  double blur_sigma = 1.0;        // pixels: Gaussian blur (the camera's point spread)
  double noise_sigma = 2.0;       // grey levels: additive Gaussian noise
  int seed = 1;                   // noise seed
};

// The image of the polygons (later ones drawn over earlier ones), anti-aliased exactly: each pixel
// takes the polygon's grey in proportion to the area of the pixel's square the polygon covers
// (the polygon clipped to the square). Then blur, noise, and rounding to 8 bits.
//
// Not cv::fillPoly: measured here, its LINE_AA mode places edges up to ~1 px off, and its plain
// mode, even at shift 8 on a 16x finer grid, fills every pixel its outline touches, which moves
// edges by up to 1/16 px depending on their phase: too much for tests of sub-pixel accuracy.
cv::Mat RenderPolygons(const std::vector<Polygon>& polygons, const SyntheticImageOptions& options);

// The polygons' sides as segments.
LineSegments PolygonSides(const std::vector<Polygon>& polygons);

}  // namespace sfm::testing

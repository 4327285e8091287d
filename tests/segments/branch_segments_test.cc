// Tests of the branch search at free segment ends (frontend/segments/branch_segments.h).
#include "frontend/segments/branch_segments.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "tests/segments/synthetic_image.h"

namespace sfm {
namespace {

using testing::Polygon;
using testing::SyntheticImageOptions;

// The fast path's gradient (fast_segments.cc): Gaussian pre-smoothing of 0.7 px (5 x 5), a 3 x 3
// Sobel pass, |gx| + |gy|, and the edge thresholds in those units.
struct Gradient {
  cv::Mat gx, gy, magnitude;
  int low = 0, high = 0;
};

Gradient GradientOf(const cv::Mat& grey, const SegmentDetectorOptions& options) {
  Gradient g;
  cv::Mat smoothed;
  const double sigma = options.fast.presmooth_sigma;
  cv::GaussianBlur(grey, smoothed, cv::Size(5, 5), sigma, sigma, cv::BORDER_REPLICATE);
  cv::spatialGradient(smoothed, g.gx, g.gy, 3, cv::BORDER_REPLICATE);
  cv::Mat ax = cv::abs(g.gx), ay = cv::abs(g.gy);
  cv::add(ax, ay, g.magnitude, cv::noArray(), CV_16S);
  const double response = 4 * std::erf(1 / (sigma * M_SQRT2));
  g.low = static_cast<int>(std::ceil(options.edge_contrast_low * response));
  g.high = static_cast<int>(std::ceil(options.edge_contrast_high * response));
  return g;
}

double LineDistance(const LineSegment& line, const Eigen::Vector2d& p) {
  return std::abs(line.Normal().dot(p - line.p0));
}

// A dark parallelogram on a brighter background with a long side (70 px) and a short side of
// 12.5 px meeting it at `corner_deg` degrees. The long side's segment is given, ending 1.5 px short
// of the corner (as a sigma = 1 px edge filter leaves it); the short side is not. The search must
// return the short side, on its true line within 0.3 px at both end-points (the junction's location
// error is then a fraction of a pixel: goal < 0.7 px median), its far end within 2 px of the true
// corner, its brighter side along Normal(), and nothing else. Four angles, two seeds.
TEST(BranchSegmentsTest, FindsTheMissingSideOfACorner) {
  const SegmentDetectorOptions options;
  for (const double corner_deg : {55.0, 75.0, 90.0, 118.0}) {
    for (int seed = 1; seed <= 2; ++seed) {
      SCOPED_TRACE("corner " + std::to_string(corner_deg) + " deg, seed " + std::to_string(seed));
      const Eigen::Vector2d a(30.3, 80.6), corner(100.2, 78.9);  // the long side a -> corner
      const Eigen::Vector2d along = (corner - a).normalized();
      const double turn = M_PI - corner_deg * M_PI / 180;  // the short side turns by this from `along`
      const Eigen::Vector2d short_dir(std::cos(turn) * along.x() - std::sin(turn) * along.y(),
                                      std::sin(turn) * along.x() + std::cos(turn) * along.y());
      const Eigen::Vector2d b = corner + 12.5 * short_dir;
      // A parallelogram: the long side a -> corner, the short side corner -> b.
      Polygon shape{{a, corner, b, a + (b - corner)}, 40};
      if ((corner - a).x() * (b - corner).y() - (corner - a).y() * (b - corner).x() < 0) {
        std::reverse(shape.vertices.begin(), shape.vertices.end());
      }
      SyntheticImageOptions image;
      image.width = 160;
      image.height = 160;
      image.background = 150;
      image.blur_sigma = 0.7;
      image.seed = seed;
      const cv::Mat grey = testing::RenderPolygons({shape}, image);
      const Gradient g = GradientOf(grey, options);
      LineSegments segments(1);
      segments[0].p0 = corner - 40 * along;  // mid-side: no corner at this end
      segments[0].p1 = corner - 1.5 * along;
      const BranchSearchStats stats =
          AppendBranchSegments(g.gx, g.gy, g.magnitude, g.low, g.high, options, &segments);
      ASSERT_EQ(segments.size(), 2u) << "free ends " << stats.free_ends;
      LineSegment truth;
      truth.p0 = corner;
      truth.p1 = b;
      const LineSegment& branch = segments[1];
      const Eigen::Vector2d far =
          (branch.p0 - corner).norm() > (branch.p1 - corner).norm() ? branch.p0 : branch.p1;
      const Eigen::Vector2d near = far == branch.p0 ? branch.p1 : branch.p0;
      EXPECT_LT(LineDistance(branch, corner), 0.3);
      EXPECT_LT(LineDistance(truth, near), 0.3);
      EXPECT_LT(std::acos(std::abs(branch.Direction().dot(short_dir))) * 180 / M_PI, 2.0);
      EXPECT_LT((far - b).norm(), 3.5);
      // Brighter side along Normal(): the background, away from the shape's inside.
      const Eigen::Vector2d inside = 0.5 * (a + b);
      EXPECT_LT(branch.Normal().dot(inside - branch.p0), 0);
    }
  }
}

// An end-point that already has a junction gets no branch: a T's stem ending on the bar, and two
// segments meeting at an L. Without the tests for other end-points and other segments nearby, the
// ray along the bar (or along the L's other side) would repeat a segment that is there.
TEST(BranchSegmentsTest, LeavesEndsThatMeetOtherSegmentsAlone) {
  const SegmentDetectorOptions options;
  SyntheticImageOptions image;
  image.width = 160;
  image.height = 160;
  image.background = 60;
  image.blur_sigma = 0.7;
  // A bright band above y = 40.5 (the bar) and a bright block right of x = 80.5 below it (the stem
  // at x = 80.5 ends on the bar); a bright square with an L corner at (40.5, 120.5).
  const std::vector<Polygon> scene = {{{{5, 5}, {155, 5}, {155, 40.5}, {5, 40.5}}, 180},
                                      {{{80.5, 40.5}, {155, 40.5}, {155, 90}, {80.5, 90}}, 120},
                                      {{{40.5, 120.5}, {70, 120.5}, {70, 150}, {40.5, 150}}, 180}};
  const Gradient g = GradientOf(testing::RenderPolygons(scene, image), options);
  LineSegments segments(4);
  segments[0].p0 = {10, 40.5};  // the bar
  segments[0].p1 = {150, 40.5};
  segments[1].p0 = {80.5, 70};  // the stem, ending 1.5 px short of the bar (its other end mid-side)
  segments[1].p1 = {80.5, 42};
  segments[2].p0 = {60, 120.5};  // the L's two sides, ending 1.5 px short of the corner
  segments[2].p1 = {42, 120.5};
  segments[3].p0 = {40.5, 122};
  segments[3].p1 = {40.5, 140};
  LineSegments out = segments;
  AppendBranchSegments(g.gx, g.gy, g.magnitude, g.low, g.high, options, &out);
  for (size_t k = segments.size(); k < out.size(); ++k) {
    ADD_FAILURE() << "branch " << out[k].p0.transpose() << " -> " << out[k].p1.transpose();
  }
}

// The a-contrario bound: in pure noise of twice the camera's sigma (4 grey levels, the rule of
// min_length), 100 random segments per 640 x 480 image give at most one branch per image on
// average (the NFA threshold is 1 per image). 20 images; measured: 0 branches.
TEST(BranchSegmentsTest, FindsAtMostOneBranchPerImageInHeavyNoise) {
  const SegmentDetectorOptions options;
  SyntheticImageOptions image;
  image.width = 640;
  image.height = 480;
  image.blur_sigma = 0;
  image.noise_sigma = 4;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(20, 620), y(20, 460), angle(0, 2 * M_PI);
  int branches = 0;
  for (int k = 0; k < 20; ++k) {
    image.seed = 100 + k;
    const Gradient g = GradientOf(testing::RenderPolygons({}, image), options);
    LineSegments segments;
    for (int i = 0; i < 100; ++i) {
      LineSegment s;
      s.p0 = {x(random), y(random)};
      const double a = angle(random);
      s.p1 = s.p0 + 20 * Eigen::Vector2d(std::cos(a), std::sin(a));
      segments.push_back(s);
    }
    const BranchSearchStats stats =
        AppendBranchSegments(g.gx, g.gy, g.magnitude, g.low, g.high, options, &segments);
    branches += stats.accepted;
  }
  EXPECT_LE(branches, 20);
}

}  // namespace
}  // namespace sfm

// The full-view canvas (--undistort_full_view): what the stored image sees beyond the undistorted
// image of its own size is detected, in K's pixel frame, and the border of the seen region makes
// no segments.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "geometry/image_undistorter.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/undistorted_segments.h"
#include "tests/test_cameras.h"

namespace sfm {
namespace {

using testing::BenchmarkLens;

// The longest of `segments` (nullptr when there are none).
const LineSegment* Longest(const LineSegments& segments) {
  const LineSegment* longest = nullptr;
  for (const LineSegment& s : segments) {
    if (!longest || s.Length() > longest->Length()) longest = &s;
  }
  return longest;
}

// The stored image of a scene given in undistorted pixels: 60 grey levels where `bright` is false,
// 160 where it is true, each stored pixel taking the value at its undistorted position (a
// 4 x 4 supersampled box, so edges are not aliased).
cv::Mat StoredImage(const Camera& camera, const std::function<bool(const Eigen::Vector2d&)>& bright) {
  cv::Mat image(camera.height, camera.width, CV_8U);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      double sum = 0;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          const Eigen::Vector2d stored(x - 0.375 + 0.25 * i, y - 0.375 + 0.25 * j);
          sum += bright(camera.HasDistortion() ? camera.UndistortPixel(stored) : stored) ? 160 : 60;
        }
      }
      image.at<uchar>(y, x) = cv::saturate_cast<uchar>(sum / 16);
    }
  }
  return image;
}

// The canvas holds every stored border pixel's undistorted position, at least the 3 px pad inside
// its own border; the margins reach the corners' undistorted positions, about 80 px left and right
// for this lens (left 75..95 px; the sides' middles alone are about 50 px out).
TEST(FullViewTest, CanvasHoldsTheWholeFieldOfView) {
  const Camera camera = BenchmarkLens();
  Eigen::Vector2d offset;
  cv::Size size;
  FullViewCanvas(camera, 3, &offset, &size);
  EXPECT_GE(offset.x(), 75);
  EXPECT_LE(offset.x(), 95);
  for (int x = 0; x < camera.width; x += 7) {
    for (int y : {0, camera.height - 1}) {
      const Eigen::Vector2d c = camera.UndistortPixel(Eigen::Vector2d(x, y)) + offset;
      EXPECT_GE(c.y(), 3 - 1e-9);
      EXPECT_LE(c.y(), size.height - 1 - 3 + 1e-9);
    }
  }
  for (int y = 0; y < camera.height; y += 7) {
    for (int x : {0, camera.width - 1}) {
      const Eigen::Vector2d c = camera.UndistortPixel(Eigen::Vector2d(x, y)) + offset;
      EXPECT_GE(c.x(), 3 - 1e-9);
      EXPECT_LE(c.x(), size.width - 1 - 3 + 1e-9);
    }
  }
  Camera pinhole = camera;
  pinhole.distortion = {0, 0, 0, 0, 0};
  const ImageUndistorter plain(pinhole, UndistortInterpolation::kLinear, UndistortView::kFullView);
  EXPECT_EQ(plain.CanvasOffset(), Eigen::Vector2d::Zero());
  EXPECT_EQ(plain.CanvasSize(), cv::Size(640, 480));
}

// A strong barrel lens given by k1 alone (-0.25, k2 = 0) folds back at the normalised radius
// sqrt(4/3) = 1.1547 (where d/dr r (1 + k1 r^2) = 1 + 3 k1 r^2 = 0), inside the stored corners'
// radius (hypot(320, 240) / 450 = 0.889 distorted, beyond the fold's largest distorted radius 0.770):
// the corners have no undistorted position, and without the fold check the
// canvas grows to 51258 x 43612 px. Protects: the fold radius to 1e-3, the benchmark lens (k2 = 0.07,
// never folds) keeping its full view, and the k1-only lens falling back to the image's own size.
TEST(FullViewTest, ALensThatFoldsBackFallsBackToTheSameSizeView) {
  Camera folding = BenchmarkLens();
  folding.distortion = {-0.25, 0, 0, 0, 0};
  EXPECT_NEAR(RadialFoldRadius(folding), std::sqrt(4.0 / 3.0), 1e-3);
  EXPECT_TRUE(std::isinf(RadialFoldRadius(BenchmarkLens())));
  const ImageUndistorter benchmark(BenchmarkLens(), UndistortInterpolation::kLinear,
                                   UndistortView::kFullView);
  EXPECT_TRUE(benchmark.FullView());
  const ImageUndistorter fallback(folding, UndistortInterpolation::kLinear, UndistortView::kFullView);
  EXPECT_FALSE(fallback.FullView());
  EXPECT_EQ(fallback.CanvasSize(), cv::Size(640, 480));
  EXPECT_EQ(fallback.CanvasOffset(), Eigen::Vector2d::Zero());
}

// An L corner of a bright quadrant at undistorted (-25, 150), which the stored image sees about
// 18 px inside its left side: found with the full view within 0.5 px of where it is in K's frame
// (the canvas offset undone), and not at all without it.
TEST(FullViewTest, FindsAJunctionBeyondTheImageSide) {
  const Camera camera = BenchmarkLens();
  const Eigen::Vector2d corner(-25, 150);
  ASSERT_TRUE(SeenByStoredImage(camera, corner, 10));
  const cv::Mat stored =
      StoredImage(camera, [&](const Eigen::Vector2d& p) { return p.x() > corner.x() && p.y() > corner.y(); });
  auto nearest = [&](UndistortView view) {
    const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, view);
    const Junctions junctions = DetectJunctions(
        DetectUndistortedSegments(undistorter, stored, SegmentDetectorOptions()), JunctionDetectorOptions());
    double best = 1e9;
    for (const Junction& j : junctions) best = std::min(best, (j.location - corner).norm());
    return best;
  };
  EXPECT_LT(nearest(UndistortView::kFullView), 0.5);
  EXPECT_GT(nearest(UndistortView::kSameSize), 20);
}

// A vertical edge at undistorted x = -20 (outside the image, seen by the stored image): its
// segment comes back in K's frame at x = -20 within 0.2 px, cut at the top and bottom where the
// stored image stops seeing it (at most 0.05 px off the border_margin line there).
TEST(FullViewTest, SegmentsComeBackInKFrameAndStopAtTheSeenBorder) {
  const Camera camera = BenchmarkLens();
  const cv::Mat stored = StoredImage(camera, [](const Eigen::Vector2d& p) { return p.x() > -20; });
  const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  const SegmentDetectorOptions options;
  const LineSegments segments = DetectUndistortedSegments(undistorter, stored, options);
  const LineSegment* longest = Longest(segments);
  ASSERT_NE(longest, nullptr);
  EXPECT_NEAR(longest->p0.x(), -20, 0.2);
  EXPECT_NEAR(longest->p1.x(), -20, 0.2);
  EXPECT_GT(longest->Length(), 300);
  for (const Eigen::Vector2d& end : {longest->p0, longest->p1}) {
    const Eigen::Vector2d d = camera.DistortPixel(end);
    const double to_border = std::min(d.y(), camera.height - 1 - d.y());
    EXPECT_NEAR(to_border, options.border_margin, 0.05) << end.transpose();
  }
}

// A pincushion lens (held-out room-dist's k1 = 0.15, k2 = -0.05) sees less than K's image, so its
// canvas is the image itself; the segments are still clipped to the seen region: a vertical edge at
// x = 60 (seen about 48 px inside the stored image's side on the middle row; the stored image's
// top and bottom cut it short of K's image border) comes back cut within 0.05 px of the 2 px line
// inside the stored image's border (unclipped, the repeated border pixels carry it on).
TEST(FullViewTest, PincushionSegmentsStopAtTheSeenBorder) {
  Camera camera = BenchmarkLens();
  camera.distortion = {0.15, -0.05, 0, 0, 0};
  const cv::Mat stored = StoredImage(camera, [](const Eigen::Vector2d& p) { return p.x() > 60; });
  const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  EXPECT_EQ(undistorter.CanvasSize(), cv::Size(640, 480));
  const SegmentDetectorOptions options;
  const LineSegments segments = DetectUndistortedSegments(undistorter, stored, options);
  const LineSegment* longest = Longest(segments);
  ASSERT_NE(longest, nullptr);
  EXPECT_NEAR(longest->p0.x(), 60, 0.2);
  EXPECT_NEAR(longest->p1.x(), 60, 0.2);
  for (const Eigen::Vector2d& end : {longest->p0, longest->p1}) {
    const Eigen::Vector2d d = camera.DistortPixel(end);
    const double to_border = std::min({d.x(), d.y(), camera.width - 1 - d.x(), camera.height - 1 - d.y()});
    EXPECT_NEAR(to_border, options.border_margin, 0.05) << end.transpose();
  }
}

// A uniform stored image has no edge: the canvas beyond the seen region repeats the border pixels,
// so the canvas itself has no segments (a black fill would put a 150-level step all round the seen
// region, and segments along it), and neither has the clipped result.
TEST(FullViewTest, NoSegmentsAlongTheBorderOfTheSeenRegion) {
  const Camera camera = BenchmarkLens();
  const cv::Mat stored(camera.height, camera.width, CV_8U, cv::Scalar(150));
  const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  EXPECT_TRUE(DetectLineSegments(undistorter.Apply(stored), SegmentDetectorOptions()).empty());
  EXPECT_TRUE(DetectUndistortedSegments(undistorter, stored, SegmentDetectorOptions()).empty());
}

// ClipSegmentsToStoredView: a segment running out of the seen region is cut where the stored image
// stops seeing it (2 px inside, within 0.02 px), one wholly inside is kept bit for bit, one wholly
// outside is dropped.
TEST(FullViewTest, ClipsToTheSeenRegion) {
  const Camera camera = BenchmarkLens();
  LineSegment across, inside, outside;
  across.p0 = Eigen::Vector2d(-200, 240.3);
  across.p1 = Eigen::Vector2d(300.7, 240.3);
  across.support = 500;
  inside.p0 = Eigen::Vector2d(100.1, 100.2);
  inside.p1 = Eigen::Vector2d(400.3, 300.4);
  outside.p0 = Eigen::Vector2d(-200, 10);
  outside.p1 = Eigen::Vector2d(-150, 10);
  LineSegments segments = {across, inside, outside};
  ClipSegmentsToStoredView(camera, 2.0, 9.0, &segments);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_NEAR(camera.DistortPixel(segments[0].p0).x(), 2.0, 0.02);
  EXPECT_EQ(segments[0].p1, across.p1);
  EXPECT_LT(segments[0].support, across.support);
  EXPECT_EQ(segments[1].p0, inside.p0);
  EXPECT_EQ(segments[1].p1, inside.p1);
}

// Without distortion the option changes nothing: the same segments, bit for bit.
TEST(FullViewTest, WithoutDistortionTheSameSegments) {
  Camera camera = BenchmarkLens();
  camera.distortion = {0, 0, 0, 0, 0};
  const cv::Mat stored = StoredImage(camera, [](const Eigen::Vector2d& p) {
    return p.x() > 100 && p.y() > 80 && p.x() + 0.3 * p.y() < 500;
  });
  const ImageUndistorter full(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  const LineSegments a = DetectUndistortedSegments(full, stored, SegmentDetectorOptions());
  const LineSegments b = DetectLineSegments(stored, SegmentDetectorOptions());
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].p0, b[i].p0);
    EXPECT_EQ(a[i].p1, b[i].p1);
  }
}

}  // namespace
}  // namespace sfm

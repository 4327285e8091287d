// ImageUndistorter's interpolation: how much each resampling blurs a sharp edge.
#include "geometry/image_undistorter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "tests/test_cameras.h"

namespace sfm {
namespace {

using testing::BenchmarkLens;

// A vertical step of 100 grey levels at undistorted x = `edge_x`, blurred with sigma 0.7 px (the
// generator's optics), as a function of the undistorted position.
double Step(double x, double edge_x) { return 60 + 100 * 0.5 * std::erfc(-(x - edge_x) / (0.7 * M_SQRT2)); }

// The stored (distorted) image of that step: each stored pixel takes the step's value at its
// undistorted position, so the ideal undistorted image is Step(x) exactly.
cv::Mat StoredImage(const Camera& camera, double edge_x) {
  cv::Mat image(camera.height, camera.width, CV_8U);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Eigen::Vector2d u = camera.UndistortPixel(Eigen::Vector2d(x, y));
      image.at<uchar>(y, x) = cv::saturate_cast<uchar>(Step(u.x(), edge_x));
    }
  }
  return image;
}

// Mean over rows 200..279 of the largest central difference (I(x+1) - I(x-1)) / 2 across the edge
// in the undistorted image, as a share of the ideal one (Step's).
double PeakGradientShare(const cv::Mat& undistorted, double edge_x) {
  const int x0 = static_cast<int>(std::floor(edge_x));
  double ideal = 0;
  for (int x = x0 - 3; x <= x0 + 4; ++x)
    ideal = std::max(ideal, (Step(x + 1, edge_x) - Step(x - 1, edge_x)) / 2);
  double sum = 0;
  int rows = 0;
  for (int y = 200; y < 280; ++y, ++rows) {
    double peak = 0;
    for (int x = x0 - 3; x <= x0 + 4; ++x) {
      peak = std::max(peak, (undistorted.at<uchar>(y, x + 1) - undistorted.at<uchar>(y, x - 1)) / 2.0);
    }
    sum += peak;
  }
  return sum / rows / ideal;
}

// The full view of make_sequence --lens equidistant's 150-degree fisheye (640 x 480, f 305.6 px):
// the canvas holds every stored pixel's undistorted position, the corners 75 degrees off axis at
// f tan(75 deg) = 1140 px from the principal point, so about 1830 x 1370 px.
TEST(ImageUndistorterTest, EquidistantFullViewHoldsTheWholeFisheyeView) {
  Camera camera = testing::GeneratorFisheye();
  EXPECT_EQ(RadialFoldRadius(camera), std::numeric_limits<double>::infinity());
  const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  ASSERT_TRUE(undistorter.FullView());
  const double corner = 305.6 * std::tan(std::hypot(320, 240) / 305.6);
  EXPECT_NEAR(undistorter.CanvasSize().width, 2 * corner * 0.8, 10);
  EXPECT_NEAR(undistorter.CanvasSize().height, 2 * corner * 0.6, 10);
  // A lens whose theta_d(theta) turns back at 60 degrees folds at tan(60 deg).
  camera.distortion = {-1 / (3 * std::pow(M_PI / 3, 2)), 0, 0, 0, 0};
  EXPECT_NEAR(RadialFoldRadius(camera), std::tan(M_PI / 3), 1e-3);
}

// The same fisheye's perspective sub-views (kSubViewCellDeg 50): 3 x 3 of them. Figures protected:
// every stored pixel (every 7th) is inside the sub-view closest to its ray, at least the margin
// less 1 px from its border; the sub-view pixel of that ray maps to the ray's undistorted pixel
// (ToUndistorted) to 1e-6 px and is seen by the stored image (SubViewSees); and the sub-view
// image at that pixel is the stored image there (a ramp of 1/8 grey level per pixel, stored
// truncated: within 1.5 grey levels; measured 0.99. A sub-view rotated the wrong way is tens off).
// A radtan lens has no sub-views.
TEST(ImageUndistorterTest, EquidistantSubViewsCoverTheFisheyeViewAndMapToK) {
  Camera camera = testing::GeneratorFisheye();
  const ImageUndistorter undistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView);
  ASSERT_EQ(undistorter.SubViews().size(), 9u);
  cv::Mat stored(camera.height, camera.width, CV_8U);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) stored.at<uchar>(y, x) = static_cast<uchar>((x + 2 * y) / 8);
  }
  std::vector<cv::Mat> views;
  for (int k = 0; k < static_cast<int>(undistorter.SubViews().size()); ++k) {
    views.push_back(undistorter.ApplySubView(k, stored));
  }
  double worst_map = 0, worst_grey = 0, closest_border = 1e9;
  for (int y = 3; y < camera.height - 3; y += 7) {
    for (int x = 3; x < camera.width - 3; x += 7) {
      const Eigen::Vector2d undistorted = camera.UndistortPixel(Eigen::Vector2d(x, y));
      const Eigen::Vector3d ray = Eigen::Vector3d((undistorted.x() - camera.cx) / camera.fx,
                                                  (undistorted.y() - camera.cy) / camera.fy, 1)
                                      .normalized();
      const int k = undistorter.SubViewOf(ray);
      const PerspectiveSubView& view = undistorter.SubViews()[k];
      const Eigen::Vector3d v = view.view_R_camera * ray;
      const Eigen::Vector2d p(view.fx * v.x() / v.z() + view.cx, view.fy * v.y() / v.z() + view.cy);
      closest_border =
          std::min({closest_border, p.x(), p.y(), view.size.width - 1 - p.x(), view.size.height - 1 - p.y()});
      worst_map = std::max(worst_map, (view.ToUndistorted(p) - undistorted).norm());
      EXPECT_TRUE(undistorter.SubViewSees(k, p, 2.0)) << x << " " << y;
      const int px = static_cast<int>(std::lround(p.x())), py = static_cast<int>(std::lround(p.y()));
      const Eigen::Vector2d back = camera.Project(view.Ray(Eigen::Vector2d(px, py)));
      const double expected = (back.x() + 2 * back.y()) / 8;
      worst_grey = std::max(worst_grey, std::abs(views[k].at<uchar>(py, px) - expected));
    }
  }
  std::printf("[ figures  ] sub-views: closest to a border %.1f px, mapping error %.2g px, grey error %.2f\n",
              closest_border, worst_map, worst_grey);
  EXPECT_GE(closest_border, 31);
  EXPECT_LT(worst_map, 1e-6);
  EXPECT_LE(worst_grey, 1.5);
  camera.model = DistortionModel::kRadTan;
  camera.distortion = {-0.2, 0.05, 0, 0, 0};
  EXPECT_TRUE(
      ImageUndistorter(camera, UndistortInterpolation::kLinear, UndistortView::kFullView).SubViews().empty());
}

TEST(ImageUndistorterTest, ParsesTheInterpolationNames) {
  UndistortInterpolation interpolation = UndistortInterpolation::kLinear;
  EXPECT_TRUE(ParseUndistortInterpolation("cubic", &interpolation));
  EXPECT_EQ(interpolation, UndistortInterpolation::kCubic);
  EXPECT_TRUE(ParseUndistortInterpolation("lanczos4", &interpolation));
  EXPECT_EQ(interpolation, UndistortInterpolation::kLanczos4);
  EXPECT_TRUE(ParseUndistortInterpolation("linear", &interpolation));
  EXPECT_EQ(interpolation, UndistortInterpolation::kLinear);
  EXPECT_FALSE(ParseUndistortInterpolation("nearest", &interpolation));
  for (const UndistortInterpolation i :
       {UndistortInterpolation::kLinear, UndistortInterpolation::kCubic, UndistortInterpolation::kLanczos4}) {
    ASSERT_TRUE(ParseUndistortInterpolation(UndistortInterpolationName(i), &interpolation));
    EXPECT_EQ(interpolation, i);
  }
}

// docs/decisions.md (interpolation): bilinear resampling blurs the
// undistorted image; cubic keeps the edges about as sharp as the stored image had them. Measured
// when written, at the stretch of the periphery (x = 560.3, d r_u / d r_s about 1.3) and near the
// centre (x = 380.6): see the printed shares. The test asks cubic for at least 0.93 of the ideal
// peak gradient at both and bilinear's to be at least 0.04 lower, so it fails if the
// interpolation argument is ignored (cubic would read as bilinear).
TEST(ImageUndistorterTest, CubicKeepsEdgesSharperThanBilinear) {
  const Camera camera = BenchmarkLens();
  for (const double edge_x : {380.6, 560.3}) {
    const cv::Mat stored = StoredImage(camera, edge_x);
    const double linear =
        PeakGradientShare(ImageUndistorter(camera, UndistortInterpolation::kLinear).Apply(stored), edge_x);
    const double cubic =
        PeakGradientShare(ImageUndistorter(camera, UndistortInterpolation::kCubic).Apply(stored), edge_x);
    const double lanczos =
        PeakGradientShare(ImageUndistorter(camera, UndistortInterpolation::kLanczos4).Apply(stored), edge_x);
    std::printf("edge at x = %.1f: peak gradient share linear %.3f, cubic %.3f, lanczos4 %.3f\n", edge_x,
                linear, cubic, lanczos);
    EXPECT_GE(cubic, 0.93) << edge_x;
    EXPECT_GE(cubic - linear, 0.04) << edge_x;
  }
}

TEST(ImageUndistorterTest, WithoutDistortionTheImageIsReturnedUnchanged) {
  Camera camera = BenchmarkLens();
  camera.distortion = {0, 0, 0, 0, 0};
  const cv::Mat stored = StoredImage(camera, 300.5);
  const cv::Mat out = ImageUndistorter(camera, UndistortInterpolation::kCubic).Apply(stored);
  EXPECT_EQ(out.data, stored.data);  // a shallow copy: no resampling at all
}

}  // namespace
}  // namespace sfm

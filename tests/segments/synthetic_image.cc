#include "tests/segments/synthetic_image.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace sfm::testing {
namespace {

using Points = std::vector<Eigen::Vector2d>;

// Sutherland-Hodgman: the part of `polygon` with (p - origin).normal >= 0.
Points ClipHalfPlane(const Points& polygon, const Eigen::Vector2d& origin, const Eigen::Vector2d& normal) {
  Points out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    const double da = (a - origin).dot(normal), db = (b - origin).dot(normal);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

double Area(const Points& polygon) {
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice);
}

// Share of pixel (x, y)'s square [x-0.5, x+0.5] x [y-0.5, y+0.5] inside the convex polygon.
double Coverage(const Points& polygon, int x, int y) {
  Points clipped = ClipHalfPlane(polygon, Eigen::Vector2d(x - 0.5, 0), Eigen::Vector2d(1, 0));
  clipped = ClipHalfPlane(clipped, Eigen::Vector2d(x + 0.5, 0), Eigen::Vector2d(-1, 0));
  clipped = ClipHalfPlane(clipped, Eigen::Vector2d(0, y - 0.5), Eigen::Vector2d(0, 1));
  clipped = ClipHalfPlane(clipped, Eigen::Vector2d(0, y + 0.5), Eigen::Vector2d(0, -1));
  return clipped.size() < 3 ? 0 : Area(clipped);
}

}  // namespace

cv::Mat RenderPolygons(const std::vector<Polygon>& polygons, const SyntheticImageOptions& options) {
  cv::Mat image(options.height, options.width, CV_32F, cv::Scalar(options.background));
  for (const Polygon& polygon : polygons) {
    Eigen::Vector2d low = polygon.vertices.front(), high = low;
    for (const Eigen::Vector2d& v : polygon.vertices) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(low.x()))), x1 = std::min(options.width - 1, static_cast<int>(std::ceil(high.x())));
    const int y0 = std::max(0, static_cast<int>(std::floor(low.y()))), y1 = std::min(options.height - 1, static_cast<int>(std::ceil(high.y())));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double share = Coverage(polygon.vertices, x, y);
        float& pixel = image.at<float>(y, x);
        pixel = static_cast<float>((1 - share) * pixel + share * polygon.grey);
      }
    }
  }
  if (options.blur_sigma > 0) cv::GaussianBlur(image, image, cv::Size(0, 0), options.blur_sigma);
  if (options.noise_sigma > 0) {
    cv::Mat noise(image.size(), CV_32F);
    cv::RNG rng(options.seed);
    rng.fill(noise, cv::RNG::NORMAL, 0, options.noise_sigma);
    image += noise;
  }
  cv::Mat grey;
  image.convertTo(grey, CV_8U);
  return grey;
}

LineSegments PolygonSides(const std::vector<Polygon>& polygons) {
  LineSegments sides;
  for (const Polygon& polygon : polygons) {
    const size_t n = polygon.vertices.size();
    for (size_t i = 0; i < n; ++i) {
      LineSegment side;
      side.p0 = polygon.vertices[i];
      side.p1 = polygon.vertices[(i + 1) % n];
      sides.push_back(side);
    }
  }
  return sides;
}

}  // namespace sfm::testing

#include "sequences/importers/plumb_line_distortion.h"

#include <Eigen/QR>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

namespace sfm {
namespace {

// Points along the chord where the edge is located, at t = 0.1 .. 0.9 (the ends, where a
// segment's end point may sit on a corner, are left out).
constexpr int kSamples = 17;
// At least this many of them must find the edge.
constexpr int kMinSamples = 12;
// The profile across the chord: +-6 px (a bow of a few pixels and the edge's blur) in 1/4 px steps.
constexpr double kProfileHalfWidthPx = 6.0;
constexpr double kProfileStepPx = 0.25;
// A gradient peak weaker than this (grey levels per profile step, on 8-bit images smoothed by the
// binomial kernel) is noise, not the edge.
constexpr double kMinGradient = 3.0;
// Half the window of the gradient's centroid: the binomial smoothing spreads a sharp edge's gradient
// over +-2 px, and the window must not reach a neighbouring edge.
constexpr double kCentroidHalfWidthPx = 2.5;
// The step of the bow's derivative in k1 (central differences): small against any real k1.
constexpr double kProbeStep = 0.001;

struct Intrinsics {
  double fx, fy, cx, cy;
  Eigen::Vector2d Distort(const Eigen::Vector2d& pixel, double k1) const {
    const Eigen::Vector2d x((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
    const double radial = 1 + k1 * x.squaredNorm();
    return Eigen::Vector2d(cx + fx * x.x() * radial, cy + fy * x.y() * radial);
  }
  // Fixed-point iteration: converges for the small |k1 r^2| of a real lens.
  Eigen::Vector2d Undistort(const Eigen::Vector2d& pixel, double k1) const {
    const Eigen::Vector2d distorted((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
    Eigen::Vector2d x = distorted;
    for (int i = 0; i < 50; ++i) x = distorted / (1 + k1 * x.squaredNorm());
    return Eigen::Vector2d(cx + fx * x.x(), cy + fy * x.y());
  }
};

// Keys' cubic convolution weights (a = -0.5) for a sample at fraction f past the second of four.
void CubicWeights(double f, double w[4]) {
  const double a = -0.5;
  auto near = [a](double d) { return ((a + 2) * d - (a + 3)) * d * d + 1; };
  auto far = [a](double d) { return ((a * d - 5 * a) * d + 8 * a) * d - 4 * a; };
  w[0] = far(1 + f);
  w[1] = near(f);
  w[2] = near(1 - f);
  w[3] = far(2 - f);
}

// Bicubic: unlike bilinear interpolation its gradient is continuous across pixel centres, so an
// edge located on it does not lock to the pixel grid.
double Sample(const cv::Mat& image, double x, double y, bool* inside) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  if (x0 < 1 || y0 < 1 || x0 >= image.cols - 2 || y0 >= image.rows - 2) {
    *inside = false;
    return 0;
  }
  double wx[4], wy[4];
  CubicWeights(x - x0, wx);
  CubicWeights(y - y0, wy);
  double value = 0;
  for (int j = 0; j < 4; ++j) {
    const float* row = image.ptr<float>(y0 - 1 + j);
    double along = 0;
    for (int i = 0; i < 4; ++i) along += wx[i] * row[x0 - 1 + i];
    value += wy[j] * along;
  }
  return value;
}

double T(int sample) { return 0.1 + 0.8 * sample / (kSamples - 1); }

// The bow: the coefficient of 4t(1-t) in a least-squares fit a + b t + bow 4t(1-t) of the offsets;
// also the fit's RMS residual.
double Bow(const std::vector<double>& t, const std::vector<double>& offset, double* rms) {
  Eigen::MatrixXd A(t.size(), 3);
  Eigen::VectorXd b(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    A.row(i) << 1, t[i], 4 * t[i] * (1 - t[i]);
    b(i) = offset[i];
  }
  const Eigen::Vector3d coefficients = A.colPivHouseholderQr().solve(b);
  if (rms) *rms = std::sqrt((A * coefficients - b).squaredNorm() / t.size());
  return coefficients(2);
}

// The image's edge across the chord at t, as an offset along the normal (pixels); false when the
// profile leaves the image or has no clear gradient peak.
bool LocateEdge(const cv::Mat& smoothed, const Eigen::Vector2d& point, const Eigen::Vector2d& normal,
                double* offset) {
  const int n = static_cast<int>(std::lround(2 * kProfileHalfWidthPx / kProfileStepPx)) + 1;
  std::vector<double> profile(n);
  bool inside = true;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = point + (-kProfileHalfWidthPx + i * kProfileStepPx) * normal;
    profile[i] = Sample(smoothed, p.x(), p.y(), &inside);
  }
  if (!inside) return false;
  std::vector<double> gradient(n);
  for (int i = 0; i < n; ++i) {
    const int a = std::max(i - 1, 0), b = std::min(i + 1, n - 1);
    gradient[i] = std::abs(profile[b] - profile[a]) / (b - a);
  }
  // The peak away from the profile's ends (a peak there is another edge beside the chord).
  int peak = 4;
  for (int i = 4; i < n - 4; ++i) {
    if (gradient[i] > gradient[peak]) peak = i;
  }
  if (gradient[peak] < kMinGradient) return false;
  // The edge is the centroid of the gradient within kCentroidHalfWidthPx of the peak. Not a
  // parabola through the peak: the profile is interpolated bilinearly between pixel centres, so its
  // gradient is constant over each pixel and a peak fit would snap to the pixel grid.
  const int half = static_cast<int>(std::lround(kCentroidHalfWidthPx / kProfileStepPx));
  double sum = 0, moment = 0;
  for (int i = std::max(peak - half, 0); i <= std::min(peak + half, n - 1); ++i) {
    sum += gradient[i];
    moment += gradient[i] * (-kProfileHalfWidthPx + i * kProfileStepPx);
  }
  *offset = moment / sum;
  return true;
}

}  // namespace

Status EstimateRadialDistortionFromEdges(const std::vector<cv::Mat>& images,
                                         const std::vector<PlumbLineSegment>& segments,
                                         const Eigen::Matrix3d& K, const PlumbLineOptions& options,
                                         PlumbLineEstimate* estimate) {
  const Intrinsics intrinsics{K(0, 0), K(1, 1), K(0, 2), K(1, 2)};
  // Binomial smoothing (1 4 6 4 1)/16 both ways: the gradient peak of a pixel-sharp edge is then
  // well sampled at quarter-pixel steps.
  std::vector<cv::Mat> smoothed(images.size());
  const cv::Mat kernel = (cv::Mat_<float>(5, 1) << 1 / 16.f, 4 / 16.f, 6 / 16.f, 4 / 16.f, 1 / 16.f);
  for (size_t i = 0; i < images.size(); ++i) {
    cv::Mat grey;
    images[i].convertTo(grey, CV_32F);
    cv::sepFilter2D(grey, smoothed[i], CV_32F, kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REFLECT);
  }
  std::vector<const PlumbLineSegment*> used;
  std::vector<double> measured;
  for (const PlumbLineSegment& segment : segments) {
    if (segment.image < 0 || static_cast<size_t>(segment.image) >= images.size()) {
      return Status::Error("plumb line: segment of image " + std::to_string(segment.image) + " out of range");
    }
    const Eigen::Vector2d chord = segment.p1 - segment.p0;
    const double length = chord.norm();
    if (!(length >= options.min_length_px)) continue;
    const Eigen::Vector2d normal(-chord.y() / length, chord.x() / length);
    std::vector<double> t, offset;
    for (int s = 0; s < kSamples; ++s) {
      double found = 0;
      if (LocateEdge(smoothed[segment.image], segment.p0 + T(s) * chord, normal, &found)) {
        t.push_back(T(s));
        offset.push_back(found);
      }
    }
    if (static_cast<int>(t.size()) < kMinSamples) continue;
    double rms = 0;
    const double bow = Bow(t, offset, &rms);
    if (rms > options.max_fit_rms_px) continue;
    used.push_back(&segment);
    measured.push_back(bow);
  }
  if (used.size() < 3) {
    return Status::Error("plumb line: " + std::to_string(used.size()) +
                         " long clean straight edges; at least 3 are needed");
  }
  // The bow k1 gives a segment: the straight line between its undistorted end points, distorted.
  std::vector<double> t_all;
  for (int s = 0; s < kSamples; ++s) t_all.push_back(T(s));
  auto predicted_bow = [&](const PlumbLineSegment& segment, double k1) {
    const Eigen::Vector2d chord = segment.p1 - segment.p0;
    const Eigen::Vector2d normal = Eigen::Vector2d(-chord.y(), chord.x()).normalized();
    const Eigen::Vector2d u0 = intrinsics.Undistort(segment.p0, k1),
                          u1 = intrinsics.Undistort(segment.p1, k1);
    std::vector<double> offset;
    for (double t : t_all)
      offset.push_back((intrinsics.Distort(u0 + t * (u1 - u0), k1) - segment.p0).dot(normal));
    return Bow(t_all, offset, nullptr);
  };
  // Gauss-Newton on sum (measured - bow(k1))^2 from k1 = 0, the derivative by central differences:
  // the bow is nearly linear in k1 (the first step is already within ~10 % for |k1| < 0.1), and a
  // few steps take out the rest.
  double k1 = 0, jj = 0, residual = 0;
  for (int iteration = 0; iteration < 5; ++iteration) {
    double jr = 0;
    jj = 0;
    residual = 0;
    for (size_t i = 0; i < used.size(); ++i) {
      const double bow = predicted_bow(*used[i], k1);
      const double slope =
          (predicted_bow(*used[i], k1 + kProbeStep) - predicted_bow(*used[i], k1 - kProbeStep)) /
          (2 * kProbeStep);
      jr += slope * (measured[i] - bow);
      jj += slope * slope;
      residual += (measured[i] - bow) * (measured[i] - bow);
    }
    if (!(jj > 0)) return Status::Error("plumb line: no edge would bow under a radial distortion");
    k1 += jr / jj;
  }
  PlumbLineEstimate result;
  result.k1 = k1;
  result.k1_sigma = std::sqrt(residual / (used.size() - 1) / jj);
  result.edges = static_cast<int>(used.size());
  *estimate = result;
  return Status::Ok();
}

}  // namespace sfm

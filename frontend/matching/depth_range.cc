#include "frontend/matching/depth_range.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <glog/logging.h>

namespace sfm {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

// parallax = scale q / (ray_z + q t_z) (ParallaxFrame), solved for q.
double InverseDepthOfParallax(const ParallaxFrame& frame, double t_z, double parallax) {
  const double s = parallax / frame.scale;
  const double denominator = 1 - s * t_z;
  return denominator > 0 ? s * frame.ray_z / denominator : kInfinity;
}

double ParallaxOfInverseDepth(const ParallaxFrame& frame, double t_z, double q) {
  if (!std::isfinite(q)) return kInfinity;
  const double denominator = frame.ray_z + q * t_z;
  return denominator > 0 ? frame.scale * q / denominator : kInfinity;
}

LocalDepthRange::LocalDepthRange(const PairGeometry& geometry, const std::vector<Eigen::Vector2d>& x1,
                                 const std::vector<Eigen::Vector2d>& x2, const std::vector<int>& source_a,
                                 const std::vector<Eigen::Vector2d>& locations_a, int neighbours,
                                 double gate_sigmas, double location_sigma_px) {
  CHECK_EQ(x1.size(), x2.size());
  CHECK_EQ(x1.size(), source_a.size());
  CHECK_GE(neighbours, 1);
  const double t_z = geometry.camera2_T_camera1.translation.z();
  // The verified correspondences' inverse depths (those whose ray has a parallax direction).
  struct Verified {
    Eigen::Vector2d x1;
    int source = -1;
    double q = 0;
  };
  std::vector<Verified> verified;
  verified.reserve(x1.size());
  for (size_t k = 0; k < x1.size(); ++k) {
    const ParallaxFrame frame = ParallaxFrameOf(geometry, x1[k]);
    if (!frame.tested) continue;
    const double q = InverseDepthOfParallax(frame, t_z, (x2[k] - frame.v).dot(frame.direction));
    if (std::isfinite(q)) verified.push_back({x1[k], source_a[k], q});
  }
  frames_.reserve(locations_a.size());
  intervals_.resize(locations_a.size());
  struct Near {
    double distance_squared;
    double q;
  };
  std::vector<Near> nearest;
  for (size_t a = 0; a < locations_a.size(); ++a) {
    frames_.push_back(ParallaxFrameOf(geometry, locations_a[a]));
    const ParallaxFrame& frame = frames_.back();
    if (!frame.tested) continue;
    nearest.clear();
    for (const Verified& v : verified) {
      if (v.source == static_cast<int>(a)) continue;
      nearest.push_back({(v.x1 - locations_a[a]).squaredNorm(), v.q});
    }
    if (nearest.empty()) continue;
    const size_t n = std::min(nearest.size(), static_cast<size_t>(neighbours));
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(n - 1), nearest.end(),
                     [](const Near& x, const Near& y) { return x.distance_squared < y.distance_squared; });
    double q_low = kInfinity, q_high = -kInfinity;
    for (size_t k = 0; k < n; ++k) {
      q_low = std::min(q_low, nearest[k].q);
      q_high = std::max(q_high, nearest[k].q);
    }
    const double tolerance = EpipolarBand(frame.sigma, location_sigma_px, gate_sigmas);
    Interval& interval = intervals_[a];
    interval.tested = true;
    interval.lo = ParallaxOfInverseDepth(frame, t_z, q_low) - tolerance;
    interval.hi = ParallaxOfInverseDepth(frame, t_z, q_high) + tolerance;
  }
}

bool LocalDepthRange::Passes(int index_a, const Eigen::Vector2d& x2) const {
  const Interval& interval = intervals_[static_cast<size_t>(index_a)];
  if (!interval.tested) return true;
  const ParallaxFrame& frame = frames_[static_cast<size_t>(index_a)];
  const double parallax = (x2 - frame.v).dot(frame.direction);
  return parallax >= interval.lo && parallax <= interval.hi;
}

}  // namespace sfm

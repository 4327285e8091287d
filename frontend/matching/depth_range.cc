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
                                 double gate_sigmas, double location_sigma_px, bool screen_verified) {
  CHECK_EQ(x1.size(), x2.size());
  CHECK_EQ(x1.size(), source_a.size());
  CHECK_GE(neighbours, 1);
  geometry_ = geometry;
  neighbours_ = static_cast<size_t>(neighbours);
  gate_sigmas_ = gate_sigmas;
  location_sigma_px_ = location_sigma_px;
  const double t_z = geometry.camera2_T_camera1.translation.z();
  // The verified correspondences' inverse depths (those whose ray has a parallax direction).
  std::vector<Verified>& verified = verified_;
  verified.reserve(x1.size());
  std::vector<std::pair<ParallaxFrame, double>> own;  // each one's frame and parallax, same order
  for (size_t k = 0; k < x1.size(); ++k) {
    const ParallaxFrame frame = ParallaxFrameOf(geometry, x1[k]);
    if (!frame.tested) continue;
    const double parallax = (x2[k] - frame.v).dot(frame.direction);
    const double q = InverseDepthOfParallax(frame, t_z, parallax);
    if (!std::isfinite(q)) continue;
    verified.push_back({x1[k], source_a[k], q, static_cast<int>(own.size())});
    own.emplace_back(frame, parallax);
  }
  // Sorted along x: the neighbour search walks outwards from a junction's x and stops on a side
  // once the x distance alone exceeds the farthest of the neighbours found.
  std::sort(verified.begin(), verified.end(), [](const Verified& u, const Verified& v) { return u.x1.x() < v.x1.x(); });
  if (screen_verified) {
    // Each verified correspondence tested against the others, by the same rule: a range is a
    // minimum and a maximum, so one wrong verified match at a near depth would widen the range of
    // every junction around it. Decided on the full set, then removed together.
    std::vector<char> keep(verified.size(), 1);
    for (size_t k = 0; k < verified.size(); ++k) {
      const auto& [frame, parallax] = own[static_cast<size_t>(verified[k].own)];
      double q_low = 0, q_high = 0;
      if (!NeighbourRange(verified[k].x1, verified[k].source, &q_low, &q_high)) continue;
      const double tolerance = EpipolarBand(frame.sigma, location_sigma_px, gate_sigmas);
      keep[k] = parallax >= ParallaxOfInverseDepth(frame, t_z, q_low) - tolerance &&
                parallax <= ParallaxOfInverseDepth(frame, t_z, q_high) + tolerance;
    }
    std::vector<Verified> kept;
    for (size_t k = 0; k < verified.size(); ++k) {
      if (keep[k]) kept.push_back(verified[k]);
    }
    verified.swap(kept);
  }
  locations_a_ = locations_a;
  frames_.resize(locations_a.size());
  intervals_.resize(locations_a.size());
  computed_.assign(locations_a.size(), 0);
}

bool LocalDepthRange::NeighbourRange(const Eigen::Vector2d& p, int exclude_source, double* q_low_out,
                                     double* q_high_out) const {
  // The nearest neighbours_ verified correspondences, unordered, with the farthest of them tracked
  // (replacing it is a scan of a handful).
  const size_t wanted = neighbours_;
  std::vector<std::pair<double, double>>& nearest = nearest_;  // (squared distance, q)
  nearest.clear();
  size_t farthest = 0;  // index in nearest of the largest distance
  const std::vector<Verified>& verified = verified_;
  const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(verified.size());
  // Offer verified[k]; false once the x distance alone rules out this side.
  auto offer = [&](std::ptrdiff_t k) {
    const Verified& v = verified[static_cast<size_t>(k)];
    const double dx = v.x1.x() - p.x();
    const bool full = nearest.size() == wanted;
    if (full && dx * dx >= nearest[farthest].first) return false;
    if (v.source == exclude_source) return true;
    const double d2 = (v.x1 - p).squaredNorm();
    if (!full) {
      nearest.emplace_back(d2, v.q);
      if (d2 > nearest[farthest].first) farthest = nearest.size() - 1;
      return true;
    }
    if (d2 >= nearest[farthest].first) return true;
    nearest[farthest] = {d2, v.q};
    for (size_t n = 0; n < nearest.size(); ++n) {
      if (nearest[n].first > nearest[farthest].first) farthest = n;
    }
    return true;
  };
  std::ptrdiff_t right = std::lower_bound(verified.begin(), verified.end(), p.x(),
                                          [](const Verified& v, double x) { return v.x1.x() < x; }) -
                         verified.begin();
  std::ptrdiff_t left = right - 1;
  while (left >= 0 || right < count) {
    // The nearer side in x first.
    const bool take_left = right >= count || (left >= 0 && p.x() - verified[static_cast<size_t>(left)].x1.x() <
                                                               verified[static_cast<size_t>(right)].x1.x() - p.x());
    if (take_left) {
      left = offer(left) ? left - 1 : -1;
    } else {
      right = offer(right) ? right + 1 : count;
    }
  }
  if (nearest.empty()) return false;
  double q_low = kInfinity, q_high = -kInfinity;
  for (const auto& [d2, q] : nearest) {
    q_low = std::min(q_low, q);
    q_high = std::max(q_high, q);
  }
  *q_low_out = q_low;
  *q_high_out = q_high;
  return true;
}

const LocalDepthRange::Interval& LocalDepthRange::IntervalOf(int index_a) const {
  const size_t a = static_cast<size_t>(index_a);
  if (computed_[a]) return intervals_[a];
  computed_[a] = 1;
  const double t_z = geometry_.camera2_T_camera1.translation.z();
  frames_[a] = ParallaxFrameOf(geometry_, locations_a_[a]);
  const ParallaxFrame& frame = frames_[a];
  if (!frame.tested) return intervals_[a];
  double q_low = 0, q_high = 0;
  if (!NeighbourRange(locations_a_[a], index_a, &q_low, &q_high)) return intervals_[a];
  const double tolerance = EpipolarBand(frame.sigma, location_sigma_px_, gate_sigmas_);
  Interval& interval = intervals_[a];
  interval.tested = true;
  interval.lo = ParallaxOfInverseDepth(frame, t_z, q_low) - tolerance;
  interval.hi = ParallaxOfInverseDepth(frame, t_z, q_high) + tolerance;
  return interval;
}

bool LocalDepthRange::Passes(int index_a, const Eigen::Vector2d& x2) const {
  const Interval& interval = IntervalOf(index_a);
  if (!interval.tested) return true;
  const ParallaxFrame& frame = frames_[static_cast<size_t>(index_a)];
  const double parallax = (x2 - frame.v).dot(frame.direction);
  return parallax >= interval.lo && parallax <= interval.hi;
}

}  // namespace sfm

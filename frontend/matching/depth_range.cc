#include "frontend/matching/depth_range.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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
  BuildGrid();
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
    BuildGrid();
  }
  locations_a_ = locations_a;
  frames_.resize(locations_a.size());
  intervals_.resize(locations_a.size());
  computed_.assign(locations_a.size(), 0);
}

void LocalDepthRange::BuildGrid() {
  grid_columns_ = grid_rows_ = 0;
  cell_start_.clear();
  if (verified_.empty()) return;
  Eigen::Vector2d low = verified_.front().x1, high = low;
  for (const Verified& v : verified_) {
    low = low.cwiseMin(v.x1);
    high = high.cwiseMax(v.x1);
  }
  // Cells holding about two verified points each on average: the search then visits a few rings.
  const Eigen::Vector2d extent = (high - low).cwiseMax(1.0);
  cell_size_ =
      std::max(1.0, std::sqrt(2.0 * extent.x() * extent.y() / static_cast<double>(verified_.size())));
  grid_origin_ = low;
  grid_columns_ = static_cast<int>(extent.x() / cell_size_) + 1;
  grid_rows_ = static_cast<int>(extent.y() / cell_size_) + 1;
  std::vector<std::pair<int, size_t>> order;  // (cell, index)
  order.reserve(verified_.size());
  for (size_t k = 0; k < verified_.size(); ++k) order.emplace_back(CellOf(verified_[k].x1), k);
  std::sort(order.begin(), order.end());
  std::vector<Verified> sorted;
  sorted.reserve(verified_.size());
  cell_start_.assign(static_cast<size_t>(grid_columns_ * grid_rows_) + 1, 0);
  for (const auto& [cell, k] : order) {
    sorted.push_back(verified_[k]);
    ++cell_start_[static_cast<size_t>(cell) + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  verified_.swap(sorted);
}

int LocalDepthRange::CellOf(const Eigen::Vector2d& x) const {
  const int column =
      std::clamp(static_cast<int>(std::floor((x.x() - grid_origin_.x()) / cell_size_)), 0, grid_columns_ - 1);
  const int row =
      std::clamp(static_cast<int>(std::floor((x.y() - grid_origin_.y()) / cell_size_)), 0, grid_rows_ - 1);
  return row * grid_columns_ + column;
}

bool LocalDepthRange::NeighbourRange(const Eigen::Vector2d& p, int exclude_source, double* q_low_out,
                                     double* q_high_out) const {
  if (cell_start_.empty()) return false;
  // The nearest neighbours_ verified correspondences, unordered, with the farthest of them tracked
  // (replacing it is a scan of a handful).
  const size_t wanted = neighbours_;
  std::vector<std::pair<double, double>>& nearest = nearest_;  // (squared distance, q)
  nearest.clear();
  size_t farthest = 0;  // index in nearest of the largest distance
  auto offer = [&](const Verified& v) {
    if (v.source == exclude_source) return;
    const double d2 = (v.x1 - p).squaredNorm();
    if (nearest.size() < wanted) {
      nearest.emplace_back(d2, v.q);
      if (d2 > nearest[farthest].first) farthest = nearest.size() - 1;
      return;
    }
    if (d2 >= nearest[farthest].first) return;
    nearest[farthest] = {d2, v.q};
    for (size_t n = 0; n < nearest.size(); ++n) {
      if (nearest[n].first > nearest[farthest].first) farthest = n;
    }
  };
  auto offer_cell = [&](int column, int row) {
    if (column < 0 || column >= grid_columns_ || row < 0 || row >= grid_rows_) return;
    const size_t cell = static_cast<size_t>(row * grid_columns_ + column);
    for (size_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) offer(verified_[k]);
  };
  // Rings of cells around p's cell (Chebyshev distance r). Every cell beyond ring r lies at least
  // r cells plus p's distance to its own cell's edges away (0 when p is outside the grid).
  const int home = CellOf(p);
  const int column = home % grid_columns_, row = home / grid_columns_;
  const Eigen::Vector2d cell_low = grid_origin_ + cell_size_ * Eigen::Vector2d(column, row);
  const double margin = std::max(0.0, std::min({p.x() - cell_low.x(), cell_low.x() + cell_size_ - p.x(),
                                                p.y() - cell_low.y(), cell_low.y() + cell_size_ - p.y()}));
  const int rings = std::max({column, grid_columns_ - 1 - column, row, grid_rows_ - 1 - row});
  for (int r = 0; r <= rings; ++r) {
    for (int j = std::max(0, row - r); j <= std::min(grid_rows_ - 1, row + r); ++j) {
      if (j == row - r || j == row + r) {
        for (int i = std::max(0, column - r); i <= std::min(grid_columns_ - 1, column + r); ++i)
          offer_cell(i, j);
      } else {
        offer_cell(column - r, j);
        offer_cell(column + r, j);
      }
    }
    const double reach = r * cell_size_ + margin;
    if (nearest.size() == wanted && nearest[farthest].first <= reach * reach) break;
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

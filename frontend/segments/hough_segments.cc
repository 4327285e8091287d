#include "frontend/segments/hough_segments.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glog/logging.h>

#include "frontend/segments/line_fit.h"

namespace sfm {
namespace {

constexpr double kDegree = M_PI / 180.0;

// The (theta, rho) accumulator with withdrawable votes and a cached maximum per theta row, so that
// finding the strongest peak after withdrawing a line's votes rescans only the rows it touched.
class HoughAccumulator {
 public:
  HoughAccumulator(cv::Size image_size, const ReferenceSegmentOptions& options)
      : angle_step_(options.hough_angle_step_deg * kDegree), rho_step_(options.hough_rho_step) {
    num_angles_ = static_cast<int>(std::lround(M_PI / angle_step_));
    angle_step_ = M_PI / num_angles_;
    window_ = static_cast<int>(std::lround(options.vote_window_deg * kDegree / angle_step_));
    const double diagonal = std::hypot(image_size.width, image_size.height);
    rho_offset_ = static_cast<int>(std::ceil(diagonal / rho_step_)) + 1;
    num_rhos_ = 2 * rho_offset_ + 1;
    cos_.resize(num_angles_);
    sin_.resize(num_angles_);
    for (int k = 0; k < num_angles_; ++k) {
      cos_[k] = std::cos(k * angle_step_);
      sin_[k] = std::sin(k * angle_step_);
    }
    votes_.assign(static_cast<size_t>(num_angles_) * num_rhos_, 0);
    dead_.assign(votes_.size(), 0);
    row_best_.assign(num_angles_, -1);
    row_dirty_.assign(num_angles_, 1);
  }

  void Vote(const EdgePoint& p, int delta) {
    // The gradient's angle modulo pi; the line normal (cos, sin) of angle k*step has rho of either
    // sign, so one half-turn of angles covers every line.
    double angle = std::atan2(p.gy, p.gx);
    if (angle < 0) angle += M_PI;
    const int centre = static_cast<int>(std::lround(angle / angle_step_));
    for (int j = centre - window_; j <= centre + window_; ++j) {
      const int k = ((j % num_angles_) + num_angles_) % num_angles_;
      const int r = static_cast<int>(std::lround((p.x * cos_[k] + p.y * sin_[k]) / rho_step_)) + rho_offset_;
      votes_[static_cast<size_t>(k) * num_rhos_ + r] += delta;
      row_dirty_[k] = 1;
    }
  }

  // The live cell with the most votes: its angle (radians), rho (pixels) and vote count.
  int Best(double* angle, double* rho, size_t* cell) {
    int best_votes = -1;
    for (int k = 0; k < num_angles_; ++k) {
      if (row_dirty_[k]) RefreshRow(k);
      if (row_best_[k] < 0) continue;
      const size_t c = static_cast<size_t>(k) * num_rhos_ + row_best_[k];
      if (votes_[c] > best_votes) {
        best_votes = votes_[c];
        *cell = c;
      }
    }
    if (best_votes < 0) return 0;
    *angle = static_cast<double>(*cell / num_rhos_) * angle_step_;
    *rho = (static_cast<int>(*cell % num_rhos_) - rho_offset_) * rho_step_;
    return best_votes;
  }

  // A cell whose line yielded no segment is never returned again.
  void Kill(size_t cell) {
    dead_[cell] = 1;
    row_dirty_[cell / num_rhos_] = 1;
  }

 private:
  void RefreshRow(int k) {
    const size_t begin = static_cast<size_t>(k) * num_rhos_;
    int best = -1, best_votes = 0;
    for (int r = 0; r < num_rhos_; ++r) {
      if (!dead_[begin + r] && votes_[begin + r] > best_votes) {
        best_votes = votes_[begin + r];
        best = r;
      }
    }
    row_best_[k] = best;
    row_dirty_[k] = 0;
  }

  double angle_step_, rho_step_;
  int num_angles_ = 0, num_rhos_ = 0, rho_offset_ = 0, window_ = 0;
  std::vector<double> cos_, sin_;
  std::vector<int> votes_;
  std::vector<uint8_t> dead_;
  std::vector<int> row_best_;
  std::vector<uint8_t> row_dirty_;
};

// The edge points bucketed in square cells, so that the points near a line are found by visiting
// only the cells its band crosses: gathering costs the line's length, not the number of points.
class PointGrid {
 public:
  PointGrid(const std::vector<EdgePoint>& points, cv::Size image_size, double cell_size)
      : cell_(cell_size),
        cols_(static_cast<int>(image_size.width / cell_size) + 1),
        rows_(static_cast<int>(image_size.height / cell_size) + 1),
        head_(static_cast<size_t>(cols_) * rows_, -1),
        next_(points.size(), -1) {
    for (size_t i = 0; i < points.size(); ++i) {
      const size_t c = static_cast<size_t>(Row(points[i].y)) * cols_ + Col(points[i].x);
      next_[i] = head_[c];
      head_[c] = static_cast<int>(i);
    }
  }

  // Calls f(point index) for every point in a cell that meets the band of half-width `distance`
  // around the line {p : normal.p = rho}.
  template <typename F>
  void ForEachNear(const Eigen::Vector2d& normal, double rho, double distance, F f) const {
    // Walk the cells across the line's main direction: columns for a line closer to horizontal.
    const bool by_column = std::abs(normal.y()) >= std::abs(normal.x());
    const double across = by_column ? normal.y() : normal.x();  // |across| >= 1/sqrt(2)
    const double along = by_column ? normal.x() : normal.y();
    const int lanes = by_column ? cols_ : rows_, depth = by_column ? rows_ : cols_;
    for (int lane = 0; lane < lanes; ++lane) {
      // The band's extent in the other coordinate over this lane [lane*cell, (lane+1)*cell].
      const double u0 = lane * cell_, u1 = (lane + 1) * cell_;
      const double v0 = (rho - along * u0) / across, v1 = (rho - along * u1) / across;
      const double margin = distance / std::abs(across);
      const int first = std::max(0, static_cast<int>(std::floor((std::min(v0, v1) - margin) / cell_)));
      const int last = std::min(depth - 1, static_cast<int>(std::floor((std::max(v0, v1) + margin) / cell_)));
      for (int cell = first; cell <= last; ++cell) {
        const size_t c = by_column ? static_cast<size_t>(cell) * cols_ + lane : static_cast<size_t>(lane) * cols_ + cell;
        for (int i = head_[c]; i >= 0; i = next_[i]) f(i);
      }
    }
  }

 private:
  int Col(float x) const { return std::clamp(static_cast<int>(x / cell_), 0, cols_ - 1); }
  int Row(float y) const { return std::clamp(static_cast<int>(y / cell_), 0, rows_ - 1); }

  double cell_;
  int cols_, rows_;
  std::vector<int> head_, next_;
};

// Indices of the unused points within `distance` of the line {p : normal.p = rho} whose gradient
// lies within the angle tolerance of the normal, keeping only the majority polarity.
std::vector<int> Gather(const std::vector<EdgePoint>& points, const PointGrid& grid, const std::vector<uint8_t>& used,
                        const Eigen::Vector2d& normal, double rho, double distance, double min_cos) {
  std::vector<int> positive, negative;
  grid.ForEachNear(normal, rho, distance, [&](int i) {
    if (used[i]) return;
    const EdgePoint& p = points[i];
    if (std::abs(normal.x() * p.x + normal.y() * p.y - rho) > distance) return;
    const double along = normal.x() * p.gx + normal.y() * p.gy;
    if (std::abs(along) < min_cos * std::hypot(p.gx, p.gy)) return;
    (along > 0 ? positive : negative).push_back(i);
  });
  return positive.size() >= negative.size() ? positive : negative;
}

FittedLine FitPoints(const std::vector<EdgePoint>& points, const std::vector<int>& indices) {
  LineFitAccumulator fit;
  for (const int i : indices) fit.Add(points[i].x, points[i].y);
  return fit.Fit();
}

// The segment fitted to points[indices] (sorted along the line), oriented with the brighter side
// along its Normal().
LineSegment FitPiece(const std::vector<EdgePoint>& points, const std::vector<int>& indices) {
  const FittedLine line = FitPoints(points, indices);
  const EdgePoint& first = points[indices.front()];
  const EdgePoint& last = points[indices.back()];
  LineSegment segment = SegmentOnLine(line, Eigen::Vector2d(first.x, first.y), Eigen::Vector2d(last.x, last.y),
                                      static_cast<int>(indices.size()));
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  for (const int i : indices) gradient += Eigen::Vector2d(points[i].gx, points[i].gy);
  if (gradient.dot(segment.Normal()) < 0) std::swap(segment.p0, segment.p1);
  return segment;
}

}  // namespace

LineSegments HoughSegments(const std::vector<EdgePoint>& points, cv::Size image_size,
                           const SegmentDetectorOptions& options) {
  const ReferenceSegmentOptions& ref = options.reference;
  HoughAccumulator accumulator(image_size, ref);
  for (const EdgePoint& p : points) accumulator.Vote(p, +1);
  std::vector<uint8_t> used(points.size(), 0);
  const PointGrid grid(points, image_size, 4.0);
  const double min_cos = std::cos(ref.angle_tolerance_deg * kDegree);

  LineSegments segments;
  std::vector<int> piece;
  std::vector<std::pair<double, int>> along;  // (position along the line, point index)
  while (true) {
    double angle = 0, rho = 0;
    size_t cell = 0;
    if (accumulator.Best(&angle, &rho, &cell) < ref.min_votes) break;
    const Eigen::Vector2d peak_normal(std::cos(angle), std::sin(angle));
    std::vector<int> support = Gather(points, grid, used, peak_normal, rho, ref.gather_distance, min_cos);
    // Two rounds of fit and re-gather: the peak's line is only as good as the accumulator's cells.
    for (int round = 0; round < 2 && support.size() >= 2; ++round) {
      const FittedLine line = FitPoints(points, support);
      const Eigen::Vector2d normal(-line.direction.y(), line.direction.x());
      support = Gather(points, grid, used, normal, normal.dot(line.centroid), ref.fit_distance, min_cos);
    }
    bool found = false;
    if (support.size() >= 2) {
      const FittedLine line = FitPoints(points, support);
      along.clear();
      for (const int i : support) along.emplace_back(line.direction.dot(Eigen::Vector2d(points[i].x, points[i].y)), i);
      std::sort(along.begin(), along.end());
      for (size_t begin = 0; begin < along.size();) {
        size_t end = begin + 1;
        while (end < along.size() && along[end].first - along[end - 1].first <= options.max_gap) ++end;
        if (end - begin >= 2 && along[end - 1].first - along[begin].first >= options.min_length) {
          piece.clear();
          for (size_t j = begin; j < end; ++j) piece.push_back(along[j].second);
          const LineSegment segment = FitPiece(points, piece);
          if (segment.Length() >= options.min_length) {
            segments.push_back(segment);
            for (const int i : piece) {
              used[i] = 1;
              accumulator.Vote(points[i], -1);
            }
            found = true;
          }
        }
        begin = end;
      }
    }
    if (!found) accumulator.Kill(cell);
  }
  return segments;
}

}  // namespace sfm

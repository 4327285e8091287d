#include "frontend/segments/collinear_merge.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sfm {
namespace {

// Pieces whose end-points are within max_gap of each other lie in the same or adjacent cells of a
// grid of square cells of side max_gap. Each cell holds a list of end-points (piece indices).
class EndGrid {
 public:
  EndGrid(const std::vector<LinePiece>& pieces, double cell_size) : cell_size_(cell_size) {
    Eigen::Vector2d low = pieces.front().first, high = low;
    for (const LinePiece& p : pieces) {
      low = low.cwiseMin(p.first).cwiseMin(p.last);
      high = high.cwiseMax(p.first).cwiseMax(p.last);
    }
    origin_ = low;
    cols_ = static_cast<int>((high.x() - low.x()) / cell_size_) + 1;
    rows_ = static_cast<int>((high.y() - low.y()) / cell_size_) + 1;
    head_.assign(static_cast<size_t>(cols_) * rows_, -1);
    for (size_t i = 0; i < pieces.size(); ++i) {
      Insert(pieces[i].first, static_cast<int>(i));
      Insert(pieces[i].last, static_cast<int>(i));
    }
  }

  // Calls f(piece index) for every end-point entry in the cells around p, until f returns true.
  template <typename F>
  bool AnyNear(const Eigen::Vector2d& p, F f) const {
    const int cx = Cell(p.x() - origin_.x(), cols_), cy = Cell(p.y() - origin_.y(), rows_);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y) {
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, cols_ - 1); ++x) {
        for (int e = head_[static_cast<size_t>(y) * cols_ + x]; e >= 0; e = next_[e]) {
          if (f(piece_[e])) return true;
        }
      }
    }
    return false;
  }

 private:
  int Cell(double offset, int size) const {
    return std::clamp(static_cast<int>(offset / cell_size_), 0, size - 1);
  }
  void Insert(const Eigen::Vector2d& p, int piece) {
    const size_t cell = static_cast<size_t>(Cell(p.y() - origin_.y(), rows_)) * cols_ + Cell(p.x() - origin_.x(), cols_);
    next_.push_back(head_[cell]);
    piece_.push_back(piece);
    head_[cell] = static_cast<int>(piece_.size()) - 1;
  }

  double cell_size_;
  Eigen::Vector2d origin_;
  int cols_ = 0, rows_ = 0;
  std::vector<int> head_, next_, piece_;
};

// Whether pieces a and b (with fitted lines line_a and line_b) continue each other; if so, the
// joined piece and its line. The tests use each piece's end-points as projected on its own line:
// a single raw edge point scatters by a few tenths of a pixel on a noisy edge, the line through all
// of them much less.
bool TryJoin(const LinePiece& a, const FittedLine& line_a, const LinePiece& b, const FittedLine& line_b,
             double max_gap, double tolerance, LinePiece* joined, FittedLine* joined_line) {
  if (a.gradient_sum.dot(b.gradient_sum) <= 0) return false;
  const std::array<Eigen::Vector2d, 4> ends = {line_a.Project(a.first), line_a.Project(a.last),
                                               line_b.Project(b.first), line_b.Project(b.last)};
  // The smallest of the four distances, by one square root (it is monotonic, so the result is the
  // same as the smallest of four square roots).
  const double gap =
      std::sqrt(std::min({(ends[0] - ends[2]).squaredNorm(), (ends[0] - ends[3]).squaredNorm(),
                          (ends[1] - ends[2]).squaredNorm(), (ends[1] - ends[3]).squaredNorm()}));
  if (gap > max_gap) return false;
  // A cheap test first: the shorter piece's ends near the longer piece's line, which the joined
  // line cannot stray far from (the longer piece's points dominate the fit).
  const bool a_longer = (ends[1] - ends[0]).squaredNorm() >= (ends[3] - ends[2]).squaredNorm();
  const FittedLine& longer = a_longer ? line_a : line_b;
  const int shorter = a_longer ? 2 : 0;
  if (std::abs(longer.Distance(ends[shorter])) > 2 * tolerance ||
      std::abs(longer.Distance(ends[shorter + 1])) > 2 * tolerance) {
    return false;
  }
  LineFitAccumulator fit = a.fit;
  fit.Merge(b.fit);
  const FittedLine line = fit.FitWithoutRms();  // the pieces' lines need no RMS
  for (const Eigen::Vector2d& e : ends) {
    if (std::abs(line.Distance(e)) > tolerance) return false;
  }
  // The joined piece keeps the raw edge points of the two outermost ends.
  const std::array<const Eigen::Vector2d*, 4> raw = {&a.first, &a.last, &b.first, &b.last};
  int lowest = 0, highest = 0;
  for (int k = 1; k < 4; ++k) {
    if (line.direction.dot(ends[k]) < line.direction.dot(ends[lowest])) lowest = k;
    if (line.direction.dot(ends[k]) > line.direction.dot(ends[highest])) highest = k;
  }
  joined->fit = fit;
  joined->first = *raw[lowest];
  joined->last = *raw[highest];
  joined->gradient_sum = a.gradient_sum + b.gradient_sum;
  *joined_line = line;
  return true;
}

}  // namespace

void MergeCollinearPieces(double max_gap, double tolerance, std::vector<LinePiece>* pieces) {
  if (pieces->size() < 2) return;
  std::vector<LinePiece>& all = *pieces;
  // A piece joined into another leaves its grid entries behind; `into` redirects them.
  std::vector<int> into(all.size());
  std::vector<FittedLine> lines(all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    into[i] = static_cast<int>(i);
    lines[i] = all[i].fit.FitWithoutRms();
  }
  auto find = [&into](int i) {
    while (into[i] != i) i = into[i] = into[into[i]];
    return i;
  };
  const EndGrid grid(all, std::max(max_gap, 1.0));
  // Every joinable pair is tried when the later of the two is reached: the grid has an entry at
  // each current end-point of every piece (a joined piece's ends are ends of its parts).
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i].merged_away) continue;
    bool joined_one = true;
    while (joined_one) {
      const Eigen::Vector2d ends[2] = {all[i].first, all[i].last};
      auto try_join = [&](int entry) {
        const int j = find(entry);
        if (j == static_cast<int>(i)) return false;
        LinePiece joined;
        FittedLine joined_line;
        if (!TryJoin(all[i], lines[i], all[j], lines[j], max_gap, tolerance, &joined, &joined_line)) return false;
        all[i] = joined;
        lines[i] = joined_line;
        all[j].merged_away = true;
        into[j] = static_cast<int>(i);
        return true;
      };
      joined_one = grid.AnyNear(ends[0], try_join) || grid.AnyNear(ends[1], try_join);
    }
  }
}

}  // namespace sfm

#include "frontend/segments/collinear_merge.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sfm {
namespace {

// Pieces whose end-points are within max_gap of each other lie in the same or adjacent cells of a
// grid of square cells of side max_gap. The entries (piece indices, one per end-point) are stored
// in cell order, so that the three cells of a row around a point are one run of the array (one
// loop, not three linked lists: the lists' ends were the merge's most mispredicted branches).
// Within a cell, entries come in reverse order of insertion.
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
    const size_t cells = static_cast<size_t>(cols_) * rows_;
    // Counting sort: begin_[c] counts cell c's entries, then (inclusive prefix sums) marks the end
    // of cell c; filling each cell from its end leaves begin_[c] at its start, begin_[c + 1] its end.
    begin_.assign(cells + 1, 0);
    for (const LinePiece& p : pieces) {
      ++begin_[CellOf(p.first)];
      ++begin_[CellOf(p.last)];
    }
    for (size_t c = 1; c < cells; ++c) begin_[c] += begin_[c - 1];
    begin_[cells] = begin_[cells - 1];
    entries_.resize(2 * pieces.size());
    for (size_t i = 0; i < pieces.size(); ++i) {
      entries_[--begin_[CellOf(pieces[i].first)]] = static_cast<int>(i);
      entries_[--begin_[CellOf(pieces[i].last)]] = static_cast<int>(i);
    }
  }

  // Calls f(piece index) for every end-point entry in the cells around p (row by row, a cell's
  // entries last inserted first), until f returns true.
  template <typename F>
  bool AnyNear(const Eigen::Vector2d& p, F f) const {
    const int cx = Cell(p.x() - origin_.x(), cols_), cy = Cell(p.y() - origin_.y(), rows_);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, cols_ - 1);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y) {
      const size_t row = static_cast<size_t>(y) * cols_;
      for (int k = begin_[row + x0], last = begin_[row + x1 + 1]; k < last; ++k) {
        if (f(entries_[k])) return true;
      }
    }
    return false;
  }

 private:
  int Cell(double offset, int size) const {
    return std::clamp(static_cast<int>(offset / cell_size_), 0, size - 1);
  }
  size_t CellOf(const Eigen::Vector2d& p) const {
    return static_cast<size_t>(Cell(p.y() - origin_.y(), rows_)) * cols_ + Cell(p.x() - origin_.x(), cols_);
  }

  double cell_size_;
  Eigen::Vector2d origin_;
  int cols_ = 0, rows_ = 0;
  std::vector<int> begin_, entries_;
};

// A piece's end-points as projected on its own fitted line (first, last).
using PieceEnds = std::array<Eigen::Vector2d, 2>;

PieceEnds ProjectedEnds(const LinePiece& piece, const FittedLine& line) {
  return {line.Project(piece.first), line.Project(piece.last)};
}

// Whether pieces a and b (with fitted lines line_a and line_b, and their end-points projected on
// them, ends_a and ends_b) continue each other; if so, the joined piece and its line. The tests use
// each piece's end-points as projected on its own line: a single raw edge point scatters by a few
// tenths of a pixel on a noisy edge, the line through all of them much less.
bool TryJoin(const LinePiece& a, const FittedLine& line_a, const PieceEnds& ends_a, const LinePiece& b,
             const FittedLine& line_b, const PieceEnds& ends_b, double max_gap, double tolerance,
             LinePiece* joined, FittedLine* joined_line) {
  const std::array<Eigen::Vector2d, 4> ends = {ends_a[0], ends_a[1], ends_b[0], ends_b[1]};
  // The smallest of the four distances, by one square root (it is monotonic, so the result is the
  // same as the smallest of four square roots).
  const double gap =
      std::sqrt(std::min({(ends[0] - ends[2]).squaredNorm(), (ends[0] - ends[3]).squaredNorm(),
                          (ends[1] - ends[2]).squaredNorm(), (ends[1] - ends[3]).squaredNorm()}));
  // Opposite polarities, or too far apart. One branch for both: the polarity alone is a coin toss
  // for the branch predictor, while nearly every pair fails one of the two.
  if ((a.gradient_sum.dot(b.gradient_sum) <= 0) | (gap > max_gap)) return false;
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
  // Each piece's projected end-points, computed once (not at every pair tested) and again when
  // the piece grows: the same operations on the same values, so the same bits.
  std::vector<PieceEnds> ends(all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    into[i] = static_cast<int>(i);
    lines[i] = all[i].fit.FitWithoutRms();
    ends[i] = ProjectedEnds(all[i], lines[i]);
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
      const Eigen::Vector2d raw_ends[2] = {all[i].first, all[i].last};
      auto try_join = [&](int entry) {
        const int j = find(entry);
        if (j == static_cast<int>(i)) return false;
        LinePiece joined;
        FittedLine joined_line;
        if (!TryJoin(all[i], lines[i], ends[i], all[j], lines[j], ends[j], max_gap, tolerance, &joined,
                     &joined_line)) {
          return false;
        }
        all[i] = joined;
        lines[i] = joined_line;
        ends[i] = ProjectedEnds(joined, joined_line);
        all[j].merged_away = true;
        into[j] = static_cast<int>(i);
        return true;
      };
      joined_one = grid.AnyNear(raw_ends[0], try_join) || grid.AnyNear(raw_ends[1], try_join);
    }
  }
}

}  // namespace sfm

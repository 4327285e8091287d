#include "frontend/junctions/segment_grid.h"

#include <algorithm>
#include <cmath>

namespace sfm {
namespace {

// Cells of about the length of a short segment: few segments share one, and a segment of typical
// length (tens of pixels) visits only a handful.
constexpr double kCellPx = 32.0;
// Bounds the grid for scattered coordinates: cells grow rather than the grid.
constexpr int kMaxCellsPerSide = 256;

}  // namespace

std::vector<std::pair<int, int>> CandidatePairs(const std::vector<SegmentLine>& lines,
                                                const std::vector<bool>& use, double reach, double pad) {
  const int n = static_cast<int>(lines.size());
  std::vector<Eigen::Vector2d> from(n), to(n);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  for (int i = 0; i < n; ++i) {
    if (!use[i]) continue;
    from[i] = lines[i].p0 - reach * lines[i].n;
    to[i] = lines[i].p1 + reach * lines[i].n;
    lo = lo.cwiseMin(from[i]).cwiseMin(to[i]);
    hi = hi.cwiseMax(from[i]).cwiseMax(to[i]);
  }
  if (!(lo.x() <= hi.x())) return {};
  lo.array() -= pad;
  hi.array() += pad;
  const double cell = std::max(kCellPx, (hi - lo).maxCoeff() / kMaxCellsPerSide);
  const int nx = static_cast<int>((hi.x() - lo.x()) / cell) + 1;
  const int ny = static_cast<int>((hi.y() - lo.y()) / cell) + 1;
  auto column = [&](double x) { return std::clamp(static_cast<int>((x - lo.x()) / cell), 0, nx - 1); };
  auto row = [&](double y) { return std::clamp(static_cast<int>((y - lo.y()) / cell), 0, ny - 1); };

  // Cells of each segment, row by row: the x-range the thickened body covers within the row's
  // y-band (conservative: a superset of the exact cells).
  std::vector<int> cells_of;  // cell indices, segment after segment
  std::vector<int> cells_begin(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    cells_begin[i] = static_cast<int>(cells_of.size());
    if (!use[i]) continue;
    const Eigen::Vector2d& a = from[i];
    const Eigen::Vector2d& b = to[i];
    const double y_min = std::min(a.y(), b.y()) - pad, y_max = std::max(a.y(), b.y()) + pad;
    for (int r = row(y_min); r <= row(y_max); ++r) {
      const double band_lo = std::max(y_min, lo.y() + r * cell);
      const double band_hi = std::min(y_max, lo.y() + (r + 1) * cell);
      double x_lo = std::min(a.x(), b.x()), x_hi = std::max(a.x(), b.x());
      const double dy = b.y() - a.y();
      if (std::abs(dy) > 1e-12) {
        // x of the centre line where it crosses the band widened by pad, clamped to the body.
        auto x_at = [&](double y) {
          const double s = std::clamp((y - a.y()) / dy, 0.0, 1.0);
          return a.x() + s * (b.x() - a.x());
        };
        const double x0 = x_at(band_lo - pad), x1 = x_at(band_hi + pad);
        x_lo = std::min(x0, x1);
        x_hi = std::max(x0, x1);
      }
      for (int c = column(x_lo - pad); c <= column(x_hi + pad); ++c) cells_of.push_back(r * nx + c);
    }
  }
  cells_begin[n] = static_cast<int>(cells_of.size());

  // Segments of each cell (counting sort into one array).
  std::vector<int> members_begin(nx * ny + 1, 0);
  for (int c : cells_of) ++members_begin[c + 1];
  for (int c = 0; c < nx * ny; ++c) members_begin[c + 1] += members_begin[c];
  std::vector<int> members(cells_of.size());
  std::vector<int> fill(members_begin.begin(), members_begin.end() - 1);
  for (int i = 0; i < n; ++i) {
    for (int k = cells_begin[i]; k < cells_begin[i + 1]; ++k) members[fill[cells_of[k]]++] = i;
  }

  std::vector<std::pair<int, int>> pairs;
  std::vector<int> last_partner_of(n, -1);  // j was already paired with i when last_partner_of[j] == i
  for (int i = 0; i < n; ++i) {
    for (int k = cells_begin[i]; k < cells_begin[i + 1]; ++k) {
      const int c = cells_of[k];
      for (int m = members_begin[c]; m < members_begin[c + 1]; ++m) {
        const int j = members[m];
        if (j <= i || last_partner_of[j] == i) continue;
        last_partner_of[j] = i;
        pairs.emplace_back(i, j);
      }
    }
  }
  return pairs;
}

}  // namespace sfm

#include "frontend/segments/branch_segments.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "frontend/segments/line_fit.h"
#include "frontend/segments/nfa.h"
#include "frontend/segments/parabola_peak.h"

namespace sfm {
namespace {

// The NFA's angle precision, as for every segment of the fast path: a sample is aligned when its
// gradient lies within 22.5 degrees of the ray's normal (LSD, EDLines).
constexpr double kAlignedProbability = 1.0 / 8;
const double kAlignedCos2 = std::pow(std::cos(M_PI * kAlignedProbability), 2);
// A branch closer than the alignment tolerance to the segment's own direction cannot be told from
// the segment's blurred end: its gradient there passes the alignment test for the ray's normal.
constexpr double kMinBranchAngle = M_PI * kAlignedProbability;
// The corner lies beyond the end-point: a sigma = 1 px edge filter stops an edge 1-2 px short of
// its corner (docs/segments.md: 1.2 px median on synthetic polygons, fast path). Rays start 1 px
// beyond the end-point.
constexpr double kCornerOffset = 1.0;
// Samples start 2 px from the ray's origin: nearer the corner the smoothed gradient mixes the two
// edges' directions (2 sigma of the edge filter).
constexpr int kFirstSample = 2;
// Segments are marked as covered from this far inside their end-points, px (MarkCovered).
constexpr double kEndMargin = 1.0;
// A run of aligned samples ends at two misaligned ones in a row (one may be a noise outlier).
constexpr int kMaxMisses = 2;
// Branches of one end-point must differ by twice the alignment tolerance (a Y or an ARROW can have
// two missing sides).
constexpr double kMinBranchSeparation = 2 * M_PI * kAlignedProbability;
constexpr int kMaxBranchesPerEnd = 2;
// PromisingDirections marks the direction steps within this many of an edge pixel's: a pixel in
// the outer ring (3-4.5 px away) places a direction to +-0.5 px / 3.75 px = +-7.6 degrees, about
// 1.5 steps; with the rounding to the nearest step, +-1 step covers it. (+-2 steps: junction recall
// 84.5 instead of 84.3 %, 25 % more branches on VGG and a slower search.)
constexpr int kSpread = 1;
// Lines closer to parallel than about 11.5 degrees give no corner (as MarkCornerLengths).
constexpr double kMinCornerSine = 0.2;
// Sub-pixel edge points across a ray are gathered this far from it, px; a point farther than this
// from the fitted line is dropped before the refit.
constexpr double kGatherDistance = 1.5;
// PromisingDirections' inner ring: the pixels 1.5-3 px from the origin's (squared distance).
constexpr double kInnerRing2 = 9;

struct Candidate {
  double log10_nfa = 0;
  double angle = 0;  // of the ray's direction, radians
  int end = 0;       // 2 * segment + (0: p0, 1: p1)
  int polarity = 0;  // +1: the gradient points along the ray's normal, -1: against it
  int last = 0;      // distance of the last aligned sample from the origin, px
};

struct RingPixel {
  int dx, dy;
  double r2, angle;
  std::ptrdiff_t offset;  // dy * cols + dx, for the current image
};

// Buffers kept per thread between images (fresh ones cost page faults and the tails' lgamma calls).
struct Workspace {
  std::vector<RingPixel> ring;    // offsets 1.5-4.5 px from a pixel, with squared length and angle
  int inner_ring = 0;             // the first inner_ring of them are 1.5-3 px away, the rest 3-4.5 px
  std::vector<double> tail;       // log10 binomial tail of (samples, aligned), (max_sample + 1)^2
  std::vector<uint64_t> covered;  // one bit per pixel: a segment passes through it
};

// The end-points (2 * segment + 0 or 1) of a segment list bucketed in square cells, for the
// searches of nearby ends (FreeEnds, Bridges, FarCornerBeyond). The points are copied in cell order,
// so that a search reads them in sequence rather than from the segments scattered in memory.
class EndGrid {
 public:
  EndGrid(const LineSegments& s, int rows, int cols, double cell) : s_(s), cell_(cell) {
    grid_cols_ = static_cast<int>(cols / cell) + 1;
    grid_rows_ = static_cast<int>(rows / cell) + 1;
    const int m = static_cast<int>(2 * s.size());
    begin_.assign(static_cast<size_t>(grid_cols_) * grid_rows_ + 1, 0);
    order_.resize(m);
    points_.resize(m);
    for (int i = 0; i < m; ++i) ++begin_[CellOf(EndPoint(i)) + 1];
    for (size_t c = 1; c < begin_.size(); ++c) begin_[c] += begin_[c - 1];
    std::vector<int> fill(begin_.begin(), begin_.end() - 1);
    for (int i = 0; i < m; ++i) {
      const int k = fill[CellOf(EndPoint(i))]++;
      order_[k] = i;
      points_[k] = EndPoint(i);
    }
  }

  const Eigen::Vector2d& EndPoint(int i) const { return i % 2 == 0 ? s_[i / 2].p0 : s_[i / 2].p1; }
  const LineSegments& Segments() const { return s_; }

  // Calls visit(j, end-point j) for the end-points j in the cells that meet the square of half-side
  // radius + 1 px around p, cell rows in order and each cell's points in order, until it returns
  // false; returns false if it did. Every end-point within `radius` of p is visited (the 1 px margin
  // keeps the rounding of p -+ radius from excluding one at exactly that distance); so is any
  // other end-point of those cells, which the caller must reject by its distance. Visiting a
  // sub-rectangle of cells keeps the order of the points a larger one would visit.
  template <typename Visit>
  bool ForEachWithin(const Eigen::Vector2d& p, double radius, Visit&& visit) const {
    const Eigen::Vector2d corner(radius + 1, radius + 1);
    int x0, y0, x1, y1;
    CellXY(p - corner, &x0, &y0);
    CellXY(p + corner, &x1, &y1);
    for (int y = y0; y <= y1; ++y) {
      // The cells x0 .. x1 of a row are consecutive in order_: one run, without a loop (and its
      // mispredicted exit) per cell.
      for (int k = begin_[y * grid_cols_ + x0], last = begin_[y * grid_cols_ + x1 + 1]; k < last; ++k) {
        if (!visit(order_[k], points_[k])) return false;
      }
    }
    return true;
  }

 private:
  // Truncation and clamping are monotonic in p, so the cells of p -+ (radius + 1) bound those of
  // every point between them (ForEachWithin).
  void CellXY(const Eigen::Vector2d& p, int* cx, int* cy) const {
    *cx = std::clamp(static_cast<int>(p.x() / cell_), 0, grid_cols_ - 1);
    *cy = std::clamp(static_cast<int>(p.y() / cell_), 0, grid_rows_ - 1);
  }
  int CellOf(const Eigen::Vector2d& p) const {
    int cx, cy;
    CellXY(p, &cx, &cy);
    return cy * grid_cols_ + cx;
  }

  const LineSegments& s_;
  double cell_;
  int grid_cols_ = 0, grid_rows_ = 0;
  std::vector<int> begin_, order_;
  std::vector<Eigen::Vector2d> points_;  // end-point order_[k], in cell order
};

class BranchSearch {
 public:
  BranchSearch(const cv::Mat& gx, const cv::Mat& gy, const cv::Mat& magnitude, int low_magnitude,
               int high_magnitude, const SegmentDetectorOptions& options, Workspace* workspace)
      : gx_(gx.ptr<int16_t>()),
        gy_(gy.ptr<int16_t>()),
        mag_(magnitude.ptr<int16_t>()),
        rows_(gx.rows),
        cols_(gx.cols),
        options_(options),
        ring_(workspace->ring),
        tail_(workspace->tail),
        covered_(workspace->covered),
        low_(low_magnitude),
        high_(high_magnitude) {
    // A branch reaches at most four minimum lengths: longer edges give chains of their own.
    max_sample_ = static_cast<int>(std::ceil(4 * options.min_length));
    // Directions 1 / (min_length + max_gap) rad apart: over the shortest branch (min_length from a
    // corner up to max_gap beyond the end) a ray half a step off drifts by half a pixel.
    step_ = 1.0 / (options.min_length + options.max_gap);
    directions_per_side_ = static_cast<int>(std::floor((M_PI - 2 * kMinBranchAngle) / step_)) + 1;
    CHECK_LE(directions_per_side_, 64) << "min_length + max_gap too large for the direction masks";
    for (int k = 0; k < directions_per_side_; ++k) {
      const double offset = kMinBranchAngle + k * step_;
      rotations_.emplace_back(std::cos(offset), std::sin(offset));
    }
    // The binomial tails of every (samples, aligned) a ray can give, kept between images.
    if (tail_.size() != static_cast<size_t>(max_sample_ + 1) * (max_sample_ + 1)) {
      tail_.assign(static_cast<size_t>(max_sample_ + 1) * (max_sample_ + 1), 0);
      for (int n = 1; n <= max_sample_; ++n) {
        for (int k = 0; k <= n; ++k)
          tail_[n * (max_sample_ + 1) + k] = Log10BinomialTail(n, k, kAlignedProbability);
      }
    }
    // The pixels 1.5-4.5 px from a pixel, with their angles (MarkPromisingDirections).
    if (ring_.empty()) {
      constexpr double kInner = 1.5, kOuter = 4.5;
      for (int dy = -4; dy <= 4; ++dy) {
        for (int dx = -4; dx <= 4; ++dx) {
          const double r2 = dx * dx + dy * dy;
          if (r2 >= kInner * kInner && r2 <= kOuter * kOuter)
            ring_.push_back({dx, dy, r2, std::atan2(dy, dx), 0});
        }
      }
      const auto outer = std::stable_partition(ring_.begin(), ring_.end(),
                                               [](const RingPixel& q) { return q.r2 <= kInnerRing2; });
      workspace->inner_ring = static_cast<int>(outer - ring_.begin());
    }
    inner_ring_ = workspace->inner_ring;
    for (RingPixel& q : ring_) q.offset = static_cast<std::ptrdiff_t>(q.dy) * cols_ + q.dx;
  }

  BranchSearchStats Run(LineSegments* segments) {
    BranchSearchStats stats;
    const LineSegments& s = *segments;
    const int n = static_cast<int>(s.size());
    std::vector<int> free_ends;
    std::vector<char> is_free;
    MarkCovered(s);
    const EndGrid grid(s, rows_, cols_, 4 * options_.max_gap);
    grid_ = &grid;
    FreeEnds(s, grid, &free_ends, &is_free);
    stats.free_ends = static_cast<int>(free_ends.size());
    if (free_ends.empty()) return stats;
    // Every (free end, direction, polarity, length) is a candidate the test could accept.
    const double tests = static_cast<double>(free_ends.size()) * 2 * directions_per_side_ * 2 *
                         (max_sample_ - kFirstSample + 1);
    log10_tests_ = std::log10(tests);
    stats.log10_tests = log10_tests_;
    std::vector<Candidate> candidates;
    std::vector<std::pair<int, double>> branch_angles;  // (free end, direction) of each branch
    for (const int end : free_ends) {
      candidates.clear();
      // A copy: the branches appended below may move the segments.
      const LineSegment segment = s[end / 2];
      const Eigen::Vector2d e = end % 2 == 0 ? segment.p0 : segment.p1;
      const Eigen::Vector2d u = end % 2 == 0 ? Eigen::Vector2d(-segment.Direction()) : segment.Direction();
      const Eigen::Vector2d origin = e + kCornerOffset * u;
      if (!OtherEdgeAt(origin, u)) continue;
      const double base = std::atan2(u.y(), u.x());
      uint64_t promising[2];
      PromisingDirections(origin, base, promising);
      for (int side = -1; side <= 1; side += 2) {
        for (uint64_t bits = promising[(side + 1) / 2]; bits != 0; bits &= bits - 1) {
          const int k = __builtin_ctzll(bits);
          Candidate c;
          c.angle = base + side * (kMinBranchAngle + k * step_);
          c.end = end;
          // u rotated by the offset, to this side.
          const double cosine = rotations_[k].x(), sine = side * rotations_[k].y();
          const Eigen::Vector2d v(cosine * u.x() - sine * u.y(), sine * u.x() + cosine * u.y());
          if (Ray(origin, v, &c)) candidates.push_back(c);
        }
      }
      std::sort(candidates.begin(), candidates.end(),
                [](const Candidate& a, const Candidate& b) { return a.log10_nfa < b.log10_nfa; });
      // Directions taken by a branch, or along an existing segment: a candidate within
      // kMinBranchSeparation of one is the same edge.
      blocked_.clear();
      int taken = 0;
      for (const Candidate& c : candidates) {
        if (taken >= kMaxBranchesPerEnd) break;
        const bool apart = std::all_of(blocked_.begin(), blocked_.end(), [&](double a) {
          return std::abs(std::remainder(a - c.angle, 2 * M_PI)) >= kMinBranchSeparation;
        });
        if (!apart) continue;
        if (AlongOtherSegment(origin, c)) {
          blocked_.push_back(c.angle);
          continue;
        }
        LineSegment branch;
        if (!Branch(segment, end / 2, e, origin, c, &branch)) continue;
        blocked_.push_back(c.angle);
        ++taken;
        branch_angles.push_back({end, c.angle});
        segments->push_back(branch);
        ++stats.accepted;
      }
    }
    stats.bridges = AppendBridges(grid, free_ends, is_free, branch_angles, segments);
    CHECK_GE(static_cast<int>(segments->size()), n);
    return stats;
  }

 private:
  // End-points (2 * segment + 0 or 1) with no other segment's end-point within 2 max_gap: two ends
  // that close can meet at a corner within max_gap of each (the reach of the corner rules in
  // fast_segments.cc), and where ends crowd like that, a branch adds a short junction among others.
  // The radius was chosen between max_gap and 2 max_gap on VGG matching precision, a figure of
  // issue 4 (docs/decisions.md): with max_gap, VGG images got 21 branches each
  // instead of 9.5 and consecutive VGG matching precision fell to 97.0-97.7 % (98.1-98.8 % with
  // 2 max_gap); keeping free the ends whose near neighbour cannot meet them at a corner gave the
  // 21 branches back. Bucketed in cells of 4 max_gap.
  void FreeEnds(const LineSegments& s, const EndGrid& grid, std::vector<int>* free_ends,
                std::vector<char>* is_free) const {
    const double gap = 2 * options_.max_gap;
    const int m = static_cast<int>(2 * s.size());
    is_free->assign(m, 0);
    for (int i = 0; i < m; ++i) {
      const Eigen::Vector2d& p = grid.EndPoint(i);
      if (!(s[i / 2].Length() > 0)) continue;
      bool alone = grid.ForEachWithin(p, gap, [&](int j, const Eigen::Vector2d& q) {
        return j / 2 == i / 2 || (q - p).squaredNorm() > gap * gap;
      });
      // An end that runs into another segment's interior within max_gap (a T's stem, or an L
      // whose other side continues past the corner) has its junction too. From 2 px on: the 3 x 3
      // pixels around a point 1 px beyond the end could hold the segment's own last marked pixel.
      const Eigen::Vector2d u = i % 2 == 0 ? Eigen::Vector2d(-s[i / 2].Direction()) : s[i / 2].Direction();
      for (int r = 2; r <= static_cast<int>(options_.max_gap) && alone; ++r) {
        int x, y;
        alone = !PixelAt(p + r * u, &x, &y) || !Covered(x, y);
      }
      if (alone) {
        free_ends->push_back(i);
        (*is_free)[i] = 1;
      }
    }
  }

  // Bridges (docs/segments.md, step 8): a segment A often stops at a
  // corner W with a third edge while its line goes on, as an edge between other faces (often of the
  // other polarity), for a few pixels more to the vertex V where a free end of a segment B stops.
  // That piece, shorter than min_length, is no chain piece and no branch (a branch must reach
  // min_length from its corner), and the pair A-B cannot make V's junction because W's took A's
  // end-point. So from each free end of B, the lines of the segments whose end-points are not
  // free (they have a corner) are continued: where A's line meets B's line within max_gap of B's
  // end (the corner X, lines at least 11.5 degrees apart), A's end-point lies more than max_gap
  // short of X (nearer, the pair test joins them directly) and at most min_length + max_gap (farther,
  // a branch could reach min_length), and the direction from X to A's end is at least 22.5 degrees
  // from B's (as a branch's), the gradient is sampled every pixel on A's line from 2 px after X to
  // 2 px before A's end-point (both are corners, where the smoothed gradient mixes two edges). The
  // samples aligned with the line's normal (22.5 degrees, the polarity of the first aligned one, at
  // the low threshold) are counted a-contrario against the family of such candidates (every
  // (free end, A end) pair that passes the geometric tests, two polarities): a few per image, not
  // the chains' 10^5 sub-runs, since two segments in this position are themselves rare in noise.
  // As for a branch, one sample must reach the high threshold and most samples must not lie on an
  // existing segment. The bridge is the piece of A's line between its first and last aligned
  // samples (A's line is fitted to many more points than the piece could give); its polarity is
  // the samples'. Returns the number of bridges appended.
  int AppendBridges(const EndGrid& grid, const std::vector<int>& free_ends, const std::vector<char>& is_free,
                    const std::vector<std::pair<int, double>>& branch_angles, LineSegments* segments) const {
    struct Bridge {
      int end;                 // B's free end, 2 * segment + 0 or 1
      Eigen::Vector2d corner;  // X, on A's line
      Eigen::Vector2d w;       // unit direction from X to A's end-point
      double gap;              // distance from X to A's end-point, px
      double log10_nfa = 0;
      int first = 0, last = 0;  // first and last aligned samples, px from X
      int polarity = 0;
      double fit_rms = 0;  // A's
    };
    const double max_bridge = options_.min_length + options_.max_gap;
    const double cos_min_angle = std::cos(kMinBranchAngle);
    // A's end-point lies within max_bridge of the corner, the corner within max_gap of B's end.
    const double reach_px = max_bridge + options_.max_gap;
    std::vector<Bridge> bridges;
    for (const int i : free_ends) {
      const LineSegment b = (*segments)[i / 2];
      const Eigen::Vector2d e = grid.EndPoint(i);
      const Eigen::Vector2d u = i % 2 == 0 ? Eigen::Vector2d(-b.Direction()) : b.Direction();
      const Eigen::Vector2d qb = b.Normal();
      grid.ForEachWithin(e, reach_px, [&](int j, const Eigen::Vector2d& ae) {
        if (j / 2 == i / 2 || is_free[j]) return true;
        if ((ae - e).squaredNorm() > reach_px * reach_px) return true;
        const LineSegment& a = (*segments)[j / 2];
        const Eigen::Vector2d out = j % 2 == 0 ? Eigen::Vector2d(-a.Direction()) : a.Direction();
        const double sine = out.x() * u.y() - out.y() * u.x();
        if (std::abs(sine) < kMinCornerSine) return true;
        // X = ae + gap * out on A's line, and on B's line: (X - e) . qb = 0.
        const double gap = (e - ae).dot(qb) / out.dot(qb);
        if (gap <= options_.max_gap || gap > max_bridge) return true;
        const Eigen::Vector2d corner = ae + gap * out;
        if ((corner - e).norm() > options_.max_gap) return true;
        const Eigen::Vector2d w = -out;
        if (std::abs(w.dot(u)) > cos_min_angle) return true;
        const double angle = std::atan2(w.y(), w.x());
        for (const auto& [end, taken] : branch_angles) {
          if (end == i && std::abs(std::remainder(taken - angle, 2 * M_PI)) < kMinBranchSeparation)
            return true;
        }
        Bridge bridge;
        bridge.end = i;
        bridge.corner = corner;
        bridge.w = w;
        bridge.gap = gap;
        bridge.fit_rms = a.fit_rms;
        bridges.push_back(bridge);
        return true;
      });
    }
    if (bridges.empty()) return 0;
    const double log10_tests = std::log10(2.0 * static_cast<double>(bridges.size()));
    std::vector<Bridge> accepted;
    for (Bridge& bridge : bridges) {
      const Eigen::Vector2d normal(-bridge.w.y(), bridge.w.x());
      const int last_sample = static_cast<int>(std::floor(bridge.gap)) - kFirstSample;
      int samples = 0, aligned = 0, covered = 0, strongest = 0, polarity = 0, first = 0, last = 0;
      for (int r = kFirstSample; r <= last_sample; ++r) {
        int x, y;
        if (!PixelAt(bridge.corner + r * bridge.w, &x, &y)) break;
        ++samples;
        if (Covered(x, y)) ++covered;
        const size_t i = static_cast<size_t>(y) * cols_ + x;
        const double g_x = gx_[i], g_y = gy_[i];
        const double along = g_x * normal.x() + g_y * normal.y();
        const bool parallel =
            mag_[i] >= low_ && along * along >= kAlignedCos2 * (g_x * g_x + g_y * g_y) && along != 0;
        if (polarity == 0 && parallel) polarity = along > 0 ? 1 : -1;
        if (parallel && along * polarity > 0) {
          if (aligned++ == 0) first = r;
          last = r;
          strongest = std::max(strongest, static_cast<int>(mag_[i]));
        }
      }
      if (samples == 0 || aligned < 2 || 2 * covered > samples || strongest < high_) continue;
      bridge.log10_nfa = log10_tests + tail_[samples * (max_sample_ + 1) + aligned];
      if (bridge.log10_nfa > options_.fast.log10_nfa_max) continue;
      bridge.first = first;
      bridge.last = last;
      bridge.polarity = polarity;
      accepted.push_back(bridge);
    }
    // Strongest first; one bridge per direction of an end, and at most kMaxBranchesPerEnd
    // branches and bridges together.
    std::stable_sort(accepted.begin(), accepted.end(),
                     [](const Bridge& a, const Bridge& b) { return a.log10_nfa < b.log10_nfa; });
    std::vector<std::pair<int, double>> taken = branch_angles;
    int appended = 0;
    for (const Bridge& bridge : accepted) {
      const double angle = std::atan2(bridge.w.y(), bridge.w.x());
      int at_end = 0;
      bool apart = true;
      for (const auto& [end, a] : taken) {
        if (end != bridge.end) continue;
        ++at_end;
        apart = apart && std::abs(std::remainder(a - angle, 2 * M_PI)) >= kMinBranchSeparation;
      }
      if (!apart || at_end >= kMaxBranchesPerEnd) continue;
      taken.push_back({bridge.end, angle});
      LineSegment piece;
      piece.p0 = bridge.corner + bridge.first * bridge.w;
      piece.p1 = bridge.corner + bridge.last * bridge.w;
      piece.support = bridge.last - bridge.first + 1;
      piece.fit_rms = bridge.fit_rms;
      const Eigen::Vector2d normal(-bridge.w.y(), bridge.w.x());
      // Brighter side along Normal() (segment_detector.h).
      if (piece.Normal().dot(bridge.polarity * normal) < 0) std::swap(piece.p0, piece.p1);
      segments->push_back(piece);
      ++appended;
    }
    return appended;
  }

  // Whether an edge other than the segment's own passes the ray origin: one of the 3 x 3 pixels
  // around it has a gradient at the low threshold and at least 22.5 degrees (the NFA's precision)
  // from the segment's normal. The corner lies about a pixel from the origin, and there the
  // missing side's gradient turns the field; where the segment's own edge only fades or dips, the
  // field keeps its normal. Only a pruning, like PromisingDirections.
  bool OtherEdgeAt(const Eigen::Vector2d& origin, const Eigen::Vector2d& u) const {
    int cx, cy;
    if (!PixelAt(origin, &cx, &cy)) return false;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const size_t i = static_cast<size_t>(cy + dy) * cols_ + cx + dx;
        if (mag_[i] < low_) continue;
        const double g_x = gx_[i], g_y = gy_[i];
        const double across = g_y * u.x() - g_x * u.y();  // along the segment's normal (-u.y, u.x)
        if (across * across < kAlignedCos2 * (g_x * g_x + g_y * g_y)) return true;
      }
    }
    return false;
  }

  // Which directions are worth a ray, as bit k of promising[side] (side 0: clockwise offsets):
  // those within two steps of an edge pixel (magnitude at least the low threshold) 1.5-3 px from
  // the origin's pixel and of one 3-4.5 px from it, each with its gradient aligned with the normal
  // of the direction from there to it. A side of a corner has edge pixels at both distances. Only
  // a pruning: a ray whose first samples miss such pixels stops at once, and the NFA still counts
  // every direction. The inner ring first: where it marks nothing, or nothing on one side, the
  // outer ring's marks there would be masked away, so its pixels are not tested.
  void PromisingDirections(const Eigen::Vector2d& origin, double base, uint64_t promising[2]) const {
    promising[0] = promising[1] = 0;
    int cx, cy;
    if (!PixelAt(origin, &cx, &cy) || cx < 5 || cy < 5 || cx >= cols_ - 5 || cy >= rows_ - 5) return;
    const size_t centre = static_cast<size_t>(cy) * cols_ + cx;
    const uint64_t every[2] = {~uint64_t{0}, ~uint64_t{0}};
    uint64_t inner[2] = {0, 0}, outer[2] = {0, 0};  // [side]
    MarkRing(centre, base, ring_.data(), ring_.data() + inner_ring_, every, inner);
    if ((inner[0] | inner[1]) == 0) return;
    MarkRing(centre, base, ring_.data() + inner_ring_, ring_.data() + ring_.size(), inner, outer);
    promising[0] = inner[0] & outer[0];
    promising[1] = inner[1] & outer[1];
  }

  // ORs into marks[side] the directions near the edge pixels among [first, last) of the ring
  // around pixel `centre` (PromisingDirections); pixels on a side where `needed` has no bit are
  // skipped.
  void MarkRing(size_t centre, double base, const RingPixel* first, const RingPixel* last,
                const uint64_t needed[2], uint64_t marks[2]) const {
    const double max_offset = kMinBranchAngle + (directions_per_side_ + 1) * step_;
    for (const RingPixel* q = first; q != last; ++q) {
      // Every test computed and combined before a single branch: one at each test mispredicted
      // often (each passes for a varying part of the ring).
      const size_t i = centre + q->offset;
      const int g_x = gx_[i], g_y = gy_[i];
      double offset = q->angle - base;
      // Wrapped by arithmetic (GCC branched on the conditional forms); subtracting or adding an exact
      // 0 leaves the value unchanged.
      offset -= static_cast<double>(offset > M_PI) * (2 * M_PI);
      offset += static_cast<double>(offset < -M_PI) * (2 * M_PI);
      const double from_min = std::abs(offset) - kMinBranchAngle;
      const int side = offset < 0 ? 0 : 1;
      const double along = g_y * q->dx - g_x * q->dy;
      const bool marked = (mag_[i] >= low_) & !(from_min < -2.5 * step_) & !(std::abs(offset) > max_offset) &
                          (needed[side] != 0) &
                          !(along * along < kAlignedCos2 * (g_x * g_x + g_y * g_y) * q->r2);
      if (!marked) continue;
      const int k = static_cast<int>(from_min / step_ + 2.5) - 2;  // rounded, for k >= -2
      const int low = std::max(k - kSpread, 0), high = std::min(k + kSpread, directions_per_side_ - 1);
      if (low > high) continue;
      marks[side] |= ((~uint64_t{0}) >> (63 - (high - low))) << low;
    }
  }

  // Marks the pixels along every segment (one per step of the major axis), 1 px in from each end:
  // a ray from an end-point, which starts beyond it, then never meets its own segment's marks. A
  // bit per pixel, so that the map stays in cache (a 512 x 512 image: 32 KB).
  void MarkCovered(const LineSegments& s) {
    // One word more, so that ThreeCoveredBits may load 8 bytes from any pixel's byte.
    covered_.assign((static_cast<size_t>(rows_) * cols_ + 63) / 64 + 1, 0);
    uint64_t* bits = covered_.data();
    for (const LineSegment& segment : s) {
      const double length = segment.Length();
      if (!(length > 2 * kEndMargin)) continue;
      const Eigen::Vector2d a = segment.p0 + kEndMargin / length * (segment.p1 - segment.p0);
      const Eigen::Vector2d d = (length - 2 * kEndMargin) / length * (segment.p1 - segment.p0);
      const int steps = static_cast<int>(std::max(std::abs(d.x()), std::abs(d.y()))) + 1;
      // Every step lies between the first and the last one (each coordinate and its rounding are
      // monotonic in i), so when both are inside, no step needs the border test.
      int x, y;
      const bool inside = PixelAt(a, &x, &y) && PixelAt(a + d, &x, &y);
      for (int i = 0; i <= steps; ++i) {
        const Eigen::Vector2d p = a + d * (static_cast<double>(i) / steps);
        if (inside) {
          x = static_cast<int>(p.x() + 0.5);
          y = static_cast<int>(p.y() + 0.5);
        } else if (!PixelAt(p, &x, &y)) {
          continue;
        }
        const size_t index = static_cast<size_t>(y) * cols_ + x;
        bits[index >> 6] |= uint64_t{1} << (index & 63);
      }
    }
  }

  // Whether more than half the ray's samples lie within about a pixel of a segment: the ray runs
  // along a segment that is there already.
  bool AlongOtherSegment(const Eigen::Vector2d& origin, const Candidate& c) const {
    const Eigen::Vector2d v(std::cos(c.angle), std::sin(c.angle));
    int covered = 0, samples = 0;
    for (int r = kFirstSample; r <= c.last; ++r) {
      int x, y;
      if (!PixelAt(origin + r * v, &x, &y)) return true;
      ++samples;
      if (Covered(x, y)) ++covered;
    }
    return 2 * covered > samples;
  }

  // Whether a segment passes within about a pixel of pixel (x, y) (not on the border): one of its
  // 3 x 3 pixels is marked. Three 3-bit loads rather than nine tests, which mispredicted often.
  bool Covered(int x, int y) const {
    const size_t index = static_cast<size_t>(y) * cols_ + x;
    return (ThreeCoveredBits(index - cols_ - 1) | ThreeCoveredBits(index - 1) |
            ThreeCoveredBits(index + cols_ - 1)) != 0;
  }

  // Bits first .. first + 2 of the covered map, from an unaligned 8-byte load (bit i of the map is
  // bit i % 8 of byte i / 8 on a little-endian machine; MarkCovered pads the map by a word).
  uint64_t ThreeCoveredBits(size_t first) const {
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the covered map is read by bytes");
    uint64_t word;
    std::memcpy(&word, reinterpret_cast<const unsigned char*>(covered_.data()) + (first >> 3), sizeof word);
    return (word >> (first & 7)) & 7;
  }

  // The pixel nearest p, or false when it lies within a pixel of the border.
  bool PixelAt(const Eigen::Vector2d& p, int* x, int* y) const {
    // Rounding as truncation of p + 0.5 (a point left of -0.5 truncates to 0 and fails the test).
    *x = static_cast<int>(p.x() + 0.5);
    *y = static_cast<int>(p.y() + 0.5);
    return *x >= 1 && *y >= 1 && *x < cols_ - 1 && *y < rows_ - 1;
  }

  // The run of aligned samples along the ray from `origin` in direction v: samples every pixel from
  // kFirstSample, the polarity set by the first aligned one, until kMaxMisses misaligned in a row.
  // Fills c's polarity, last and log10 NFA; false when no run could be a segment.
  bool Ray(const Eigen::Vector2d& origin, const Eigen::Vector2d& v, Candidate* c) const {
    const Eigen::Vector2d normal(-v.y(), v.x());
    int polarity = 0, misses = 0, aligned = 0, aligned_at_last = 0, last = 0;
    // The ray is a segment: when both its ends are inside, every sample is.
    int x, y;
    const bool inside =
        PixelAt(origin + kFirstSample * v, &x, &y) && PixelAt(origin + max_sample_ * v, &x, &y);
    for (int r = kFirstSample; r <= max_sample_; ++r) {
      const Eigen::Vector2d p = origin + r * v;
      if (inside) {
        x = static_cast<int>(p.x() + 0.5);
        y = static_cast<int>(p.y() + 0.5);
      } else if (!PixelAt(p, &x, &y)) {
        break;
      }
      const size_t i = static_cast<size_t>(y) * cols_ + x;
      // |gx| + |gy| from the two loads rather than a third array (the search is bound by memory).
      const int ix = gx_[i], iy = gy_[i];
      const double g_x = ix, g_y = iy;
      const double along = g_x * normal.x() + g_y * normal.y();
      const bool parallel = std::abs(ix) + std::abs(iy) >= low_ &&
                            along * along >= kAlignedCos2 * (g_x * g_x + g_y * g_y) && along != 0;
      if (polarity == 0 && parallel) polarity = along > 0 ? 1 : -1;
      if (parallel && along * polarity > 0) {
        ++aligned;
        aligned_at_last = aligned;
        last = r;
        misses = 0;
      } else if (++misses >= kMaxMisses) {
        break;
      }
    }
    // Too short to reach min_length from a corner at most max_gap behind the origin: not a branch.
    if (last + options_.max_gap + kCornerOffset < options_.min_length) return false;
    const int samples = last - kFirstSample + 1;
    c->polarity = polarity;
    c->last = last;
    c->log10_nfa = log10_tests_ + tail_[samples * (max_sample_ + 1) + aligned_at_last];
    return c->log10_nfa <= options_.fast.log10_nfa_max;
  }

  // A branch whose far end stops at another corner: how far beyond
  // its far end-point `far` (direction d) its line meets the line of another segment (not
  // `exclude`, the segment it starts from) at a corner, or 0. As the short sides between two corners
  // (docs/segments.md, step 7): a rounded corner takes 1-2 px off each end of a side, so a side of
  // 10-12 px between two corners gives a branch of 7-9 px, and it is measured from corner to corner.
  // The far corner lies within max_gap of `far` and within max_gap of an end-point of the other
  // segment (an L), or on its interior (the branch ends on it, a T); lines at least 11.5 degrees
  // apart (so a 0.2 px line error moves the corner by under 1 px).
  double FarCornerBeyond(const Eigen::Vector2d& far, const Eigen::Vector2d& d, int exclude) const {
    const double gap = options_.max_gap;
    double best = 0;
    grid_->ForEachWithin(far, 2 * gap, [&](int j, const Eigen::Vector2d& end) {
      if (j / 2 == exclude) return true;
      if ((end - far).squaredNorm() > 4 * gap * gap) return true;
      const LineSegment& other = grid_->Segments()[j / 2];
      const Eigen::Vector2d od = other.Direction();
      const double sine = d.x() * od.y() - d.y() * od.x();
      if (std::abs(sine) < kMinCornerSine) return true;
      // Y = far + beyond * d on the other segment's line: (Y - end) . normal = 0.
      const Eigen::Vector2d on = other.Normal();
      const double beyond = (end - far).dot(on) / d.dot(on);
      const Eigen::Vector2d y = far + beyond * d;
      if (std::abs(beyond) > gap || (y - end).norm() > gap) return true;
      best = std::max(best, beyond);
      return true;
    });
    // A T: the points 1..max_gap px beyond the far end run into another segment's interior.
    for (int r = 1; r <= static_cast<int>(gap); ++r) {
      int x, y;
      if (!PixelAt(far + r * d, &x, &y)) break;
      if (Covered(x, y)) {
        best = std::max(best, static_cast<double>(r));
        break;
      }
    }
    return best;
  }

  // The branch of candidate c: a line fitted to the sub-pixel edge points across the ray, checked
  // for its corner with `segment` (end-point e) and its length from that corner.
  bool Branch(const LineSegment& segment, int segment_index, const Eigen::Vector2d& e,
              const Eigen::Vector2d& origin, const Candidate& c, LineSegment* branch) const {
    const Eigen::Vector2d v(std::cos(c.angle), std::sin(c.angle)), normal(-v.y(), v.x());
    // Across the ray: along the image axis closest to its normal (as the chains' sub-pixel points).
    const bool across_y = std::abs(normal.y()) >= std::abs(normal.x());
    const int step = across_y ? cols_ : 1;
    std::vector<Eigen::Vector2d> points;
    int samples = 0, strongest = 0;
    for (int r = kFirstSample; r <= c.last; ++r) {
      const Eigen::Vector2d p = origin + r * v;
      int x, y;
      if (!PixelAt(p, &x, &y)) return false;
      ++samples;
      // The magnitude maximum among the pixel and its two neighbours across the ray.
      int best = y * cols_ + x;
      for (int k = -1; k <= 1; k += 2) {
        const int q = y * cols_ + x + k * step;
        const int qx = q % cols_, qy = q / cols_;
        if (qx >= 1 && qy >= 1 && qx < cols_ - 1 && qy < rows_ - 1 && mag_[q] > mag_[best]) best = q;
      }
      const std::optional<double> delta = ParabolaPeakOffset(mag_[best - step], mag_[best], mag_[best + step]);
      if (!delta) continue;
      strongest = std::max(strongest, static_cast<int>(mag_[best]));
      const Eigen::Vector2d point = across_y ? Eigen::Vector2d(best % cols_, best / cols_ + *delta)
                                             : Eigen::Vector2d(best % cols_ + *delta, best / cols_);
      if (std::abs(normal.dot(point - origin)) <= kGatherDistance) points.push_back(point);
    }
    if (points.size() < 3 || strongest < high_) return false;
    LineFitAccumulator fit;
    for (const Eigen::Vector2d& p : points) fit.Add(p);
    FittedLine line = fit.Fit();
    std::vector<Eigen::Vector2d> kept;
    for (const Eigen::Vector2d& p : points) {
      if (std::abs(line.Distance(p)) <= options_.fast.line_tolerance) kept.push_back(p);
    }
    // Most samples must give an edge point on one line (a ray across texture gives scattered ones).
    if (3 * kept.size() < 2 * static_cast<size_t>(samples) || kept.size() < 3) return false;
    LineFitAccumulator refit;
    for (const Eigen::Vector2d& p : kept) refit.Add(p);
    line = refit.Fit();
    // As the chains' pieces (fast_segments.cc, SplitChain): the line is refitted without the end
    // points farther than half the tolerance from it, the corner's arc, which tilts a short line;
    // the end-points stay the projections of the outermost points.
    const double seed_tolerance = 0.5 * options_.fast.line_tolerance;
    for (size_t first = 0, last = kept.size(); last - first > 3;) {
      if (std::abs(line.Distance(kept[first])) > seed_tolerance) {
        refit.Remove(kept[first++]);
      } else if (std::abs(line.Distance(kept[last - 1])) > seed_tolerance) {
        refit.Remove(kept[--last]);
      } else {
        break;
      }
      line = refit.Fit();
    }
    fit = refit;
    if (line.direction.dot(v) < 0) line.direction = -line.direction;
    if (line.direction.dot(v) < std::cos(M_PI * kAlignedProbability)) return false;
    // The corner: the branch's line meets the segment's line near the end-point.
    const Eigen::Vector2d d = segment.Direction();
    const double sine = d.x() * line.direction.y() - d.y() * line.direction.x();
    if (std::abs(sine) < kMinCornerSine) return false;
    const Eigen::Vector2d q = segment.Normal();
    const double s = -q.dot(line.centroid - segment.p0) / q.dot(line.direction);
    const Eigen::Vector2d corner = line.centroid + s * line.direction;
    if ((corner - e).norm() > options_.max_gap) return false;
    *branch = SegmentOnLine(line, kept.front(), kept.back(), fit.count());
    const Eigen::Vector2d far = line.Project(kept.back());
    double length = (far - corner).dot(line.direction);
    if (length < options_.min_length) length += FarCornerBeyond(far, line.direction, segment_index);
    if (length < options_.min_length) return false;
    // Brighter side along Normal() (segment_detector.h): the gradient's polarity across the ray.
    if (branch->Normal().dot(c.polarity * normal) < 0) std::swap(branch->p0, branch->p1);
    return true;
  }

  const int16_t* gx_;
  const int16_t* gy_;
  const int16_t* mag_;
  const int rows_, cols_;
  const SegmentDetectorOptions& options_;
  int max_sample_ = 0, directions_per_side_ = 0;
  double step_ = 0, log10_tests_ = 0;
  std::vector<RingPixel>& ring_;
  int inner_ring_ = 0;  // ring_[0, inner_ring_): the pixels 1.5-3 px away
  std::vector<double>& tail_;
  std::vector<uint64_t>& covered_;
  std::vector<double> blocked_;             // directions of one end already explained (Run)
  const EndGrid* grid_ = nullptr;           // the input segments' end-points (Run)
  std::vector<Eigen::Vector2d> rotations_;  // cosine and sine of each direction's angle from the segment
  // The edge thresholds in |gx| + |gy| units: as on a chain, every aligned sample reaches the low
  // one and the branch's strongest edge point the high one (an anchor).
  int low_ = 0, high_ = 0;
};

}  // namespace

BranchSearchStats AppendBranchSegments(const cv::Mat& gx, const cv::Mat& gy, const cv::Mat& magnitude,
                                       int low_magnitude, int high_magnitude,
                                       const SegmentDetectorOptions& options, LineSegments* segments) {
  CHECK_EQ(gx.type(), CV_16S);
  CHECK_EQ(gy.type(), CV_16S);
  CHECK_EQ(magnitude.type(), CV_16S);
  CHECK(gx.isContinuous() && gy.isContinuous() && magnitude.isContinuous());
  if (gx.rows < 3 || gx.cols < 3) return {};
  thread_local Workspace workspace;
  return BranchSearch(gx, gy, magnitude, low_magnitude, high_magnitude, options, &workspace).Run(segments);
}

}  // namespace sfm

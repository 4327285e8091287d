#include "frontend/segments/fast_segments.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "frontend/segments/branch_segments.h"
#include "frontend/segments/collinear_merge.h"
#include "frontend/segments/line_fit.h"
#include "frontend/segments/nfa.h"
#include "frontend/segments/parabola_peak.h"
#include "frontend/segments/sobel_gradient.h"

namespace sfm {
namespace {

// Added to a pixel's direction (kAlongX, kAlongY) once it is on a chain: the direction map doubles
// as the chains' map, so no separate map is cleared and read for every image.
constexpr uint8_t kOnChain = 4;
static_assert((kOnChain & (kAlongX | kAlongY)) == 0, "kOnChain is a bit of its own");

// The angle precision of the NFA test: a sample is aligned when its gradient is within 22.5 degrees
// of the segment's normal (LSD's and EDLines' value).
constexpr double kAlignedProbability = 1.0 / 8;
const double kAlignedCos2 = std::pow(std::cos(M_PI * kAlignedProbability), 2);

// Peak of |gx| (3x3 Sobel) across an ideal step edge of one grey level, after Gaussian smoothing of
// scale sigma: the central difference across the blurred step, erf(1 / (sigma sqrt 2)), times the
// Sobel's 1+2+1 weights along the edge.
double SobelStepResponse(double sigma) { return sigma > 0 ? 4 * std::erf(1 / (sigma * M_SQRT2)) : 4.0; }

// Buffers of the detector, kept per thread between calls: fresh multi-megabyte buffers for every
// image cost page faults comparable to the whole detection (measured: 0.3-0.5 ms per 512x512 image).
struct Workspace {
  cv::Mat smoothed;
  cv::Mat gx, gy;       // CV_16S Sobel derivatives
  cv::Mat magnitude;    // CV_16S |gx| + |gy|
  cv::Mat direction;    // CV_8U kAlongX, kAlongY, or 0 (below the low threshold or on the border),
                        // with kOnChain added once the pixel is on a chain
  std::vector<int> anchors, backward, forward, chain;  // pixel indices y * cols + x
  std::vector<uint8_t> row_marks;                      // 1 at a row's anchors
  std::vector<Eigen::Vector2d> points;                 // sub-pixel points of chain
  std::vector<LinePiece> pieces;                       // straight pieces of all chains
  std::vector<std::pair<size_t, size_t>> ranges;       // chain points [begin, end) of the current chain's pieces
  std::vector<FittedLine> lines;                       // their fitted lines (MarkCornerLengths)
  // Log10BinomialTail(n, k, kAlignedProbability) at [n][k], NaN until first needed (Validate): the
  // same few (n, k) recur in every image, and each evaluation costs three lgamma and a series.
  std::vector<std::vector<double>> binomial_tails;
};

// One image's detection.
class FastDetector {
 public:
  FastDetector(const cv::Mat& grey, const SegmentDetectorOptions& options, Workspace* workspace)
      : options_(options),
        rows_(grey.rows),
        cols_(grey.cols),
        gx_(workspace->gx),
        gy_(workspace->gy),
        magnitude_(workspace->magnitude),
        direction_(workspace->direction),
        anchors_(workspace->anchors),
        row_marks_(workspace->row_marks),
        backward_(workspace->backward),
        forward_(workspace->forward),
        chain_(workspace->chain),
        points_(workspace->points),
        pieces_(workspace->pieces),
        ranges_(workspace->ranges),
        lines_(workspace->lines),
        binomial_tails_(workspace->binomial_tails) {
    pieces_.clear();
    const cv::Mat* smoothed = &grey;
    const double sigma = options.fast.presmooth_sigma;
    if (sigma > 0) {
      const int size = 2 * static_cast<int>(std::ceil(2 * sigma)) + 1;
      cv::GaussianBlur(grey, workspace->smoothed, cv::Size(size, size), sigma, sigma, cv::BORDER_REPLICATE);
      smoothed = &workspace->smoothed;
    }
    const double response = SobelStepResponse(sigma);
    low_ = std::max(1, static_cast<int>(std::ceil(options.edge_contrast_low * response)));
    high_ = std::max(low_, static_cast<int>(std::ceil(options.edge_contrast_high * response)));
    // One pass: the derivatives are not written and read back before the magnitude.
    SobelMagnitude(*smoothed, low_, &gx_, &gy_, &magnitude_, &direction_);
    // Room for the longest possible walk (Walk); a no-op after the first image of this size.
    const size_t pixels = static_cast<size_t>(rows_) * cols_;
    if (backward_.size() < pixels) backward_.resize(pixels);
    if (forward_.size() < pixels) forward_.resize(pixels);
    min_pixels_ = std::max(3, static_cast<int>(std::ceil(options.min_length / M_SQRT2)));
  }

  LineSegments Run() {
    FindAnchors();
    const int16_t* mag = magnitude_.ptr<int16_t>();
    uint8_t* dir = direction_.ptr<uint8_t>();
    for (const int anchor : anchors_) {
      if (dir[anchor] & kOnChain) continue;
      const bool along_x = dir[anchor] == kAlongX;
      dir[anchor] |= kOnChain;
      const size_t backward = Walk(anchor, along_x ? -1 : 0, along_x ? 0 : -1, mag, dir, backward_.data());
      const size_t forward = Walk(anchor, along_x ? +1 : 0, along_x ? 0 : +1, mag, dir, forward_.data());
      if (backward + forward + 1 < static_cast<size_t>(min_pixels_)) continue;
      chain_.assign(std::make_reverse_iterator(backward_.begin() + backward), backward_.rend());
      chain_.push_back(anchor);
      chain_.insert(chain_.end(), forward_.begin(), forward_.begin() + forward);
      // Every sub-run of the chain is a candidate segment: L (L + 1) / 2 tests.
      const double length = static_cast<double>(chain_.size());
      num_tests_ += 0.5 * length * (length + 1);
      const size_t first_piece = pieces_.size();
      ranges_.clear();
      const size_t first_break = SplitChain();
      // A closed contour has no natural start: the anchor may lie mid-side, which would cut that
      // side in two. Start it again where its first piece ended, which is a corner.
      const bool closed = IsClosed();
      if (pieces_.size() - first_piece >= 2 && closed) {
        pieces_.resize(first_piece);
        ranges_.clear();
        std::rotate(chain_.begin(), chain_.begin() + static_cast<std::ptrdiff_t>(first_break), chain_.end());
        SplitChain();
      }
      MarkCornerLengths(first_piece, closed);
    }
    // A piece joined across chains is one more candidate: count every piece once more.
    num_tests_ += static_cast<double>(pieces_.size());
    // Short sides between two corners are a family of candidates of their own (see Validate).
    double short_sides = 0;
    for (const LinePiece& piece : pieces_) {
      if (piece.corner_length >= options_.min_length) ++short_sides;
    }
    log10_short_side_tests_ = std::log10(std::max(short_sides, 1.0));
    MergeCollinearPieces(options_.max_gap, options_.fast.line_tolerance, &pieces_);
    log10_tests_ = std::log10(std::max(num_tests_, 1.0));
    LineSegments segments;
    for (const LinePiece& piece : pieces_) {
      if (!piece.merged_away) Validate(piece, &segments);
    }
    AppendBranchSegments(gx_, gy_, magnitude_, low_, high_, options_, &segments);
    return segments;
  }

 private:
  // Pixels above the high threshold that are maxima across the edge (strict on one side, so a
  // plateau of two equal pixels gives one anchor), in raster order. A branch-free pass marks each
  // row's anchors; the marks are then collected eight at a time, skipping empty words.
  void FindAnchors() {
    anchors_.clear();
    // The bounds in locals: the mark stores may alias any member, so a loop bound read from cols_
    // would be reloaded after every store, and that alone blocked vectorisation.
    const int rows = rows_, cols = cols_;
    row_marks_.assign(cols + 8, 0);
    uint8_t* marks = row_marks_.data();
    const int16_t high = static_cast<int16_t>(high_);
    for (int y = 1; y + 1 < rows; ++y) {
      AnchorRow(magnitude_.ptr<int16_t>(y - 1), magnitude_.ptr<int16_t>(y), magnitude_.ptr<int16_t>(y + 1),
                direction_.ptr<uint8_t>(y), cols, high, marks);
      static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "marks are read as little-endian words");
      // Each mark is a byte of 0 or 1, so a word's set bits are its anchors, lowest x first (the
      // bytes of a little-endian word): taking them by count-trailing-zeros spares the byte loop's
      // mispredicted branches. Marks from cols_ - 1 on stay 0 (never written after the assign).
      const int row = y * cols;
      for (int x = 1; x + 1 < cols; x += 8) {
        uint64_t word;
        std::memcpy(&word, marks + x, sizeof(word));
        for (; word != 0; word &= word - 1) anchors_.push_back(row + x + __builtin_ctzll(word) / 8);
      }
    }
  }

  // FindAnchors' marks of one row (not of the border rows): 1 where the magnitude reaches `high`
  // and is a maximum across the edge. Branch-free, with restrict parameters (see SobelMagnitude), so
  // that the compiler vectorises it. Here a pixel reaching `high` is alive (its direction is not 0):
  // SobelMagnitude sets a direction wherever the magnitude reaches the low threshold <= high,
  // except on the border rows and columns, which this loop does not visit.
  static void AnchorRow(const int16_t* __restrict up, const int16_t* __restrict mag,
                        const int16_t* __restrict down, const uint8_t* __restrict dir, int cols, int16_t high,
                        uint8_t* __restrict marks) {
    for (int x = 1; x + 1 < cols; ++x) {
      // All four neighbours are loaded unconditionally: a conditional load blocks vectorisation.
      const int16_t m = mag[x], above = up[x], below = down[x], left = mag[x - 1], right = mag[x + 1];
      // across_y ? above : left, and the same for after, as masks (SSE2 has no blend).
      const int16_t across_y = static_cast<int16_t>(-(dir[x] == kAlongX));
      const int16_t before = static_cast<int16_t>((above & across_y) | (left & ~across_y));
      const int16_t after = static_cast<int16_t>((below & across_y) | (right & ~across_y));
      marks[x] = static_cast<uint8_t>((m >= high) & (m > before) & (m >= after));
    }
  }

  // ED's routing: from `index`, step to the strongest of the three pixels ahead in the travel
  // direction (dx, dy) (one of them zero) while it is alive and on no chain; the travel axis follows
  // each pixel's edge direction. Writes the pixels visited to out, which has room for every pixel
  // of the image (a walk visits each at most once), and returns their number. A plain array
  // rather than push_back: the direction map's byte stores (kOnChain) may alias a vector's
  // pointers, which were then reloaded at every step.
  size_t Walk(int index, int dx, int dy, const int16_t* mag, uint8_t* dir, int* out) const {
    const int stride = cols_;
    size_t count = 0;
    while (true) {
      const int middle = index + dx + dy * stride;
      const int side = dx != 0 ? stride : 1;
      int next = middle, offset = 0;
      if (mag[middle - side] > mag[next]) next = middle - side, offset = -1;
      if (mag[middle + side] > mag[next]) next = middle + side, offset = +1;
      // Alive and on no chain: kAlongX or kAlongY without kOnChain (0 is dead).
      const uint8_t direction = dir[next];
      if (direction != kAlongX && direction != kAlongY) return count;
      dir[next] = direction | kOnChain;
      out[count++] = next;
      const int move_x = dx != 0 ? dx : offset;
      const int move_y = dy != 0 ? dy : offset;
      if (direction == kAlongX) {
        dx = move_x != 0 ? move_x : (mag[next + 1] >= mag[next - 1] ? 1 : -1);
        dy = 0;
      } else {
        dy = move_y != 0 ? move_y : (mag[next + stride] >= mag[next - stride] ? 1 : -1);
        dx = 0;
      }
      index = next;
    }
  }

  // The sub-pixel edge point of a chain pixel: the vertex of the parabola through the magnitudes
  // across the edge, when the pixel is their maximum (Devernay's localisation).
  Eigen::Vector2d SubpixelPoint(int index) const {
    const int16_t* mag = magnitude_.ptr<int16_t>();
    const bool along_x = (direction_.ptr<uint8_t>()[index] & ~kOnChain) == kAlongX;
    const int step = along_x ? cols_ : 1;
    const double delta = ParabolaPeakOffset(mag[index - step], mag[index], mag[index + step]).value_or(0.0);
    const int y = index / cols_, x = index % cols_;
    return along_x ? Eigen::Vector2d(x, y + delta) : Eigen::Vector2d(x + delta, y);
  }

  // Whether the chain's two ends are 8-neighbours.
  bool IsClosed() const {
    const int a = chain_.front(), b = chain_.back();
    return chain_.size() > 2 && std::abs(a % cols_ - b % cols_) <= 1 && std::abs(a / cols_ - b / cols_) <= 1;
  }

  // EDLines' splitting: fit the first min_pixels_ points; if they are straight, extend the line
  // point by point while each next point is within the tolerance, then start again after it.
  // Three rules for corners, where the chain turns through a rounded arc:
  //  - the seed window must be straight to half the tolerance (SeedTolerance). With the full
  //    tolerance a window holding the arc and the first pixels of the next side passes as a line
  //    at some middle angle, and that piece eats the start of the side: a short side (a box's
  //    bottom edge, 10-15 px) was left with too few points to be a segment;
  //  - a piece also grows backwards, over the points the seed search skipped since the previous
  //    piece, while they are within the seed tolerance of its line: the side keeps its length;
  //  - its line is refitted without the end points beyond the seed tolerance (below).
  // Returns the chain index where the first piece ended (the chain's size if there is none).
  size_t SplitChain() {
    ComputePoints();
    return SplitRange(0, chain_.size(), static_cast<size_t>(min_pixels_));
  }

  void ComputePoints() {
    points_.resize(chain_.size());
    for (size_t i = 0; i < chain_.size(); ++i) points_[i] = SubpixelPoint(chain_[i]);
  }

  // The splitting of SplitChain over chain points [begin, n) with seed windows of `window` points.
  size_t SplitRange(size_t begin, size_t n, size_t window) {
    const double tolerance = options_.fast.line_tolerance, seed_tolerance = SeedTolerance(tolerance);
    size_t start = begin, previous_end = begin, first_break = n;
    while (start + window <= n) {
      LineFitAccumulator fit;
      for (size_t i = start; i < start + window; ++i) fit.Add(points_[i]);
      FittedLine line = fit.FitWithoutRms();
      bool straight = true;
      for (size_t i = start; i < start + window && straight; ++i) {
        straight = std::abs(line.Distance(points_[i])) <= seed_tolerance;
      }
      if (!straight) {
        ++start;
        continue;
      }
      // The line is refitted after every point (EDLines' rule): each test uses the best estimate.
      size_t end = start + window;
      while (end < n && std::abs(line.Distance(points_[end])) <= tolerance) {
        fit.Add(points_[end]);
        line = fit.FitWithoutRms();
        ++end;
      }
      while (start > previous_end && std::abs(line.Distance(points_[start - 1])) <= seed_tolerance) {
        fit.Add(points_[--start]);
        line = fit.FitWithoutRms();
      }
      // The growth's tolerance lets the first pixels of a corner's arc in, and they tilt a short
      // line: the line is refitted without the end points farther than the seed tolerance from it
      // (refitting after each). The piece still spans [start, end): its end-points stay the
      // projections of its outermost edge points, as the paper defines them.
      size_t first = start, last = end;
      while (last - first > window) {
        if (std::abs(line.Distance(points_[last - 1])) > seed_tolerance) {
          fit.Remove(points_[--last]);
        } else if (std::abs(line.Distance(points_[first])) > seed_tolerance) {
          fit.Remove(points_[first++]);
        } else {
          break;
        }
        line = fit.FitWithoutRms();
      }
      AddPiece(start, end, fit);
      if (first_break == n) first_break = end;
      start = previous_end = end;
    }
    return first_break;
  }

  // The seed window's tolerance: half the growth tolerance, but never below the scatter of
  // sub-pixel points on a straight edge (kMinSeedTolerance), so that a small line_tolerance still
  // finds seeds on noisy edges.
  static double SeedTolerance(double tolerance) { return std::max(0.5 * tolerance, std::min(tolerance, kMinSeedTolerance)); }
  static constexpr double kMinSeedTolerance = 0.5;
  // Pixels left out of the NFA's samples at each end (Validate): the scale of the edge filter
  // (presmoothing and Sobel together: sigma = 1 px at the default), over which a corner's second
  // edge bends the gradient.
  static constexpr double kEndTrim = 1.0;
  // Chain points that may lie between a short side and its neighbours (MarkCornerLengths): the
  // corner's arc left out of both pieces.
  static constexpr size_t kMaxCornerSkip = 3;
  // Lines closer to parallel than about 11.5 degrees give no corner: a line error of 0.2 px would
  // move their intersection by more than 1 px.
  static constexpr double kMinCornerSine = 0.2;

  // A side of a polygon-like chain shorter than min_length: rounded corners shorten every detected
  // side by 1-2 px at each end (more at acute corners), so a true side of 10-12 px comes out as a
  // piece of 7-9 px. A piece whose chain continues, within kMaxCornerSkip points at both ends,
  // into pieces at least min_length long (or which closes on itself) has corners at both ends; its
  // corner_length is the distance between the intersections of its line with theirs, when each
  // intersection lies within max_gap of its own end (a corner, not a near-parallel continuation).
  // Validate measures such a piece by that length. `first`: its chain's first piece.
  void MarkCornerLengths(size_t first, bool closed) {
    const size_t count = pieces_.size() - first, n = chain_.size();
    if (count < 3) return;
    std::vector<FittedLine>& lines = lines_;  // of this chain's pieces, from `first`
    lines.clear();
    for (size_t k = first; k < pieces_.size(); ++k) lines.push_back(pieces_[k].fit.FitWithoutRms());
    auto long_enough = [&](size_t k) {
      const LinePiece& p = pieces_[first + k];
      return (lines[k].Project(p.last) - lines[k].Project(p.first)).norm() >= options_.min_length;
    };
    for (size_t k = 0; k < count; ++k) {
      if (!closed && (k == 0 || k + 1 == count)) continue;
      const size_t before = (k + count - 1) % count, after = (k + 1) % count;
      if (!long_enough(before) || !long_enough(after)) continue;
      // Points between the pieces, around the chain when it is closed.
      const size_t skip_before = (ranges_[k].first + n - ranges_[before].second) % n;
      const size_t skip_after = (ranges_[after].first + n - ranges_[k].second) % n;
      if (skip_before > kMaxCornerSkip || skip_after > kMaxCornerSkip) continue;
      LinePiece& piece = pieces_[first + k];
      const Eigen::Vector2d ends[2] = {lines[k].Project(piece.first), lines[k].Project(piece.last)};
      Eigen::Vector2d corners[2];
      bool ok = true;
      for (int e = 0; e < 2 && ok; ++e) {
        ok = Intersect(lines[k], lines[e == 0 ? before : after], &corners[e]) &&
             (corners[e] - ends[e]).norm() <= options_.max_gap;
      }
      if (ok) piece.corner_length = (corners[1] - corners[0]).norm();
    }
  }

  // The common point of two lines, if they are at least kMinCornerSine from parallel.
  static bool Intersect(const FittedLine& a, const FittedLine& b, Eigen::Vector2d* point) {
    const double sine = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
    if (std::abs(sine) < kMinCornerSine) return false;
    // a.centroid + s a.direction lies on b: b.Distance(...) = 0.
    const double s = -b.Distance(a.centroid) / (b.direction.x() * a.direction.y() - b.direction.y() * a.direction.x());
    *point = a.centroid + s * a.direction;
    return true;
  }

  // Records chain points [begin, end), fitted by `fit`, as a piece.
  void AddPiece(size_t begin, size_t end, const LineFitAccumulator& fit) {
    ranges_.emplace_back(begin, end);
    LinePiece piece;
    piece.fit = fit;
    piece.first = points_[begin];
    piece.last = points_[end - 1];
    const int16_t* gx = gx_.ptr<int16_t>();
    const int16_t* gy = gy_.ptr<int16_t>();
    long sum_x = 0, sum_y = 0;
    for (size_t i = begin; i < end; ++i) {
      sum_x += gx[chain_[i]];
      sum_y += gy[chain_[i]];
    }
    piece.gradient_sum = Eigen::Vector2d(static_cast<double>(sum_x), static_cast<double>(sum_y));
    pieces_.push_back(piece);
  }

  // Appends the piece's segment, oriented by its polarity, if it is long enough and meaningful:
  // its NFA, from the gradient sampled every pixel along the segment, is small enough. The samples
  // start and end kEndTrim px inside the end-points: an end-point lies a pixel or two short of the
  // corner where its edge meets another, and there the smoothed gradient mixes both edges'
  // directions, so end samples fail the alignment test on real corners, not only on noise. Short
  // sides of boxes, bevels and frames (10-15 px, a corner at each end) lost up to 4 of their ~12
  // samples that way and were rejected. In noise a sample is aligned with probability 1/8 wherever
  // it lies, so leaving the end samples out keeps the test's bound on false alarms.
  void Validate(const LinePiece& piece, LineSegments* segments) const {
    LineSegment segment = SegmentOnLine(piece.fit.Fit(), piece.first, piece.last, piece.fit.count());
    const double length = segment.Length();
    // A short side between two corners (MarkCornerLengths) counts by its corner-to-corner length,
    // and is tested against the family of such sides only: its number of tests is their count,
    // tens to hundreds per image, not the chains' sub-runs.
    const bool short_side = length < options_.min_length && piece.corner_length >= options_.min_length;
    if ((length < options_.min_length && !short_side) || !(length > 0)) return;
    Eigen::Vector2d normal = segment.Normal();
    if (normal.dot(piece.gradient_sum) < 0) {
      std::swap(segment.p0, segment.p1);
      normal = -normal;
    }
    const int16_t* gx = gx_.ptr<int16_t>();
    const int16_t* gy = gy_.ptr<int16_t>();
    const double sampled = std::max(0.0, length - 2 * kEndTrim);
    const int samples = static_cast<int>(sampled) + 1;
    const Eigen::Vector2d direction = (segment.p1 - segment.p0) / length;
    const Eigen::Vector2d first = segment.p0 + (0.5 * (length - sampled)) * direction;
    const Eigen::Vector2d step = samples > 1 ? Eigen::Vector2d(direction * (sampled / (samples - 1))) : Eigen::Vector2d::Zero();
    int aligned = 0;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector2d p = first + i * step;
      // Rounding as truncation of p + 0.5 (p >= -0.5 here; a point farther out is clamped anyway).
      const int x = std::clamp(static_cast<int>(p.x() + 0.5), 0, cols_ - 1);
      const int y = std::clamp(static_cast<int>(p.y() + 0.5), 0, rows_ - 1);
      const double g_x = gx[y * cols_ + x], g_y = gy[y * cols_ + x];
      const double along = g_x * normal.x() + g_y * normal.y();
      if (along > 0 && along * along >= kAlignedCos2 * (g_x * g_x + g_y * g_y)) ++aligned;
    }
    const double log10_tests = short_side ? log10_short_side_tests_ : log10_tests_;
    // Log10Nfa(samples, aligned, kAlignedProbability, log10_tests), its tail looked up.
    if (log10_tests + BinomialTail(samples, aligned) > options_.fast.log10_nfa_max) return;
    segments->push_back(segment);
  }

  // Log10BinomialTail(n, k, kAlignedProbability), computed once per (n, k) and thread.
  double BinomialTail(int n, int k) const {
    if (binomial_tails_.size() <= static_cast<size_t>(n)) binomial_tails_.resize(n + 1);
    std::vector<double>& row = binomial_tails_[n];
    if (row.empty()) row.assign(n + 1, std::numeric_limits<double>::quiet_NaN());
    double& tail = row[k];
    if (std::isnan(tail)) tail = Log10BinomialTail(n, k, kAlignedProbability);
    return tail;
  }

  const SegmentDetectorOptions& options_;
  const int rows_, cols_;
  int low_ = 0, high_ = 0, min_pixels_ = 0;
  double num_tests_ = 0, log10_tests_ = 0;  // candidate segments tested by the NFA (see Run)
  double log10_short_side_tests_ = 0;       // log10 of the number of short sides between corners
  // Views of the workspace's buffers (see Workspace for their contents).
  cv::Mat& gx_;
  cv::Mat& gy_;
  cv::Mat& magnitude_;
  cv::Mat& direction_;
  std::vector<int>& anchors_;
  std::vector<uint8_t>& row_marks_;
  std::vector<int>& backward_;
  std::vector<int>& forward_;
  std::vector<int>& chain_;
  std::vector<Eigen::Vector2d>& points_;
  std::vector<LinePiece>& pieces_;
  std::vector<std::pair<size_t, size_t>>& ranges_;
  std::vector<FittedLine>& lines_;
  std::vector<std::vector<double>>& binomial_tails_;
};

}  // namespace

LineSegments DetectFastSegments(const cv::Mat& grey, const SegmentDetectorOptions& options) {
  CHECK_EQ(grey.type(), CV_8UC1);
  if (grey.rows < 3 || grey.cols < 3) return {};
  thread_local Workspace workspace;
  const cv::Mat continuous = grey.isContinuous() ? grey : grey.clone();
  return FastDetector(continuous, options, &workspace).Run();
}

}  // namespace sfm

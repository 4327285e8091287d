#include "frontend/matching/junction_similarity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <glog/logging.h>

#include "frontend/matching/endpoint_support.h"
#include "frontend/matching/physical_constraints.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Distance of (x, y) from a line (a, b, c) with |(a, b)| = 1; one expression for every caller, so
// that the candidate scan and the test of each pair agree to the last bit. The sum in the order of
// Eigen's line.dot(x.homogeneous()) ((a x + b y) + c), which it replaced: the same bits.
double DistanceToLine(const Eigen::Vector3d& line, double x, double y) {
  return std::abs(line(0) * x + line(1) * y + line(2));
}
double DistanceToLine(const Eigen::Vector3d& line, const Eigen::Vector2d& x) {
  return DistanceToLine(line, x.x(), x.y());
}

// True when segments a and b of one junction (its unit directions and detected line segments) are
// one line through it, as junction detection reads a T's bar (docs/junctions.md, "Type"): both
// from one detected line segment, or pointing opposite ways within the angle whose sine is min_sin.
bool OneLine(const Eigen::Vector2d* directions, const int* line_segments, int a, int b, double min_sin) {
  if (line_segments[a] >= 0 && line_segments[a] == line_segments[b]) return true;
  const double cross = directions[a].x() * directions[b].y() - directions[a].y() * directions[b].x();
  return directions[a].dot(directions[b]) < 0 && std::abs(cross) < min_sin;
}

// The pairs among segments indices[0..n) of a junction that are OneLine.
int LinesThrough(const Eigen::Vector2d* directions, const int* line_segments, const int* indices, int n,
                 double min_sin) {
  int lines = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j)
      lines += OneLine(directions, line_segments, indices[i], indices[j], min_sin);
  }
  return lines;
}

}  // namespace

double Rho1(double d, double d_prime, double R, Rho1Kind kind) {
  switch (kind) {
    case Rho1Kind::kExponential: {
      const double w = std::log(100.0) / R;  // exp(-w R) = 0.01
      return 0.5 * (std::exp(-w * d) + std::exp(-w * d_prime));
    }
    case Rho1Kind::kLinear:
      return 0.5 * (2 - (d + d_prime) / R);
  }
  return 0;
}

JunctionSimilarity::Side JunctionSimilarity::MakeSide(const Junctions& junctions, const Eigen::Matrix3d& F) {
  Side side;
  side.first.reserve(junctions.size());
  side.count.reserve(junctions.size());
  side.location_line.reserve(junctions.size());
  for (const Junction& junction : junctions) {
    side.first.push_back(static_cast<int>(side.segments.size()));
    side.count.push_back(junction.NumSegments());
    side.location.push_back(junction.location);
    const Eigen::Vector3d line = F * junction.location.homogeneous();
    const double norm = line.head<2>().norm();
    side.location_line_norm.push_back(norm);
    // A location at the epipole has no epipolar line: no distance is within R of it.
    side.location_line.push_back(norm > 0 ? Eigen::Vector3d(line / norm)
                                          : Eigen::Vector3d(0, 0, std::numeric_limits<double>::infinity()));
    for (const JunctionSegment& segment : junction.segments) {
      side.segments.push_back(OrientedSegment::FromPoints(junction.location, segment.end));
      side.directions.push_back(side.segments.back().direction);
      side.line_segments.push_back(segment.line_segment);
      side.epipolar.push_back(MakeEndpointEpipolar(F, side.segments.back()));
    }
  }
  return side;
}

JunctionSimilarity::JunctionSimilarity(const Junctions& a, const Junctions& b, const Eigen::Matrix3d& F,
                                       const MatchingOptions& options)
    : options_(options),
      min_sin_(std::sin(options.cyclic_order_min_angle_deg * kPi / 180)),
      side_a_(MakeSide(a, F)),
      side_b_(MakeSide(b, F.transpose())) {
  b_x_.reserve(b.size());
  b_y_.reserve(b.size());
  for (const Junction& junction : b) {
    b_x_.push_back(junction.location.x());
    b_y_.push_back(junction.location.y());
  }
}

void JunctionSimilarity::PossiblePartners(int index_a, std::vector<int>* out,
                                          int max_count_difference) const {
  const int n = side_a_.count[index_a];
  if (n == 0) return;
  const double bound = has_geometry_ && options_.use_pose_band ? side_a_.deviation_bound[index_a]
                                                                : options_.max_epipolar_distance_px;
  // The two tests Rho starts with; d' computed as LocationsAgree does (DistanceToLine), so that the
  // list holds exactly the pairs whose d' passes there. A loop without a temporary row: this runs
  // for every junction of a in every pass.
  // b's coordinates and counts in separate arrays, so that the loop reads them contiguously.
  const Eigen::Vector3d& line = side_a_.location_line[index_a];
  const int num_b = static_cast<int>(b_x_.size());
  const double* x = b_x_.data();
  const double* y = b_y_.data();
  const int* count = side_b_.count.data();
  for (int j = 0; j < num_b; ++j) {
    if (DistanceToLine(line, x[j], y[j]) <= bound && std::abs(count[j] - n) <= max_count_difference) {
      out->push_back(j);
    }
  }
}

JunctionSimilarity::JunctionSimilarity(const Junctions& a, const Junctions& b, const PairGeometry& geometry,
                                       const MatchingOptions& options)
    : JunctionSimilarity(a, b, geometry.Fundamental(), options) {
  has_geometry_ = true;
  geometry_ = geometry;
  inverse_geometry_ = InversePairGeometry(geometry);
  // The cheirality frames are computed on first use (ParallaxOf): most locations never reach the
  // test, which comes after the band tests.
  for (Side* side : {&side_a_, &side_b_}) {
    side->parallax.resize(side->location.size());
    side->parallax_tolerance.resize(side->location.size());
    side->parallax_known.assign(side->location.size(), 0);
  }
  Eigen::Matrix3d G[6];
  geometry.FundamentalDeviations(G);
  side_a_.deviation.reserve(a.size());
  // sigma_e = |(G p0)^T p'0| is convex in p'0, so over the bounding box of b's locations it is
  // largest at a corner: a bound for the cheap rejection in Rho.
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const Eigen::Vector2d& location : side_b_.location) {
    low = low.cwiseMin(location);
    high = high.cwiseMax(location);
  }
  for (const Junction& junction : a) {
    Eigen::Matrix<double, 3, 6> deviation;
    for (int k = 0; k < 6; ++k) deviation.col(k) = G[k] * junction.location.homogeneous();
    side_a_.deviation.push_back(deviation);
    double sigma_e = 0;
    if (!b.empty()) {
      for (const Eigen::Vector2d& corner : {low, high, Eigen::Vector2d(low.x(), high.y()), Eigen::Vector2d(high.x(), low.y())}) {
        sigma_e = std::max(sigma_e, (deviation.transpose() * corner.homogeneous()).norm());
      }
    }
    const double norm = side_a_.location_line_norm[side_a_.deviation.size() - 1];
    side_a_.deviation_bound.push_back(EpipolarBand(norm > 0 ? sigma_e / norm : std::numeric_limits<double>::infinity(),
                                                   options.location_sigma_px, options.band_sigmas));
  }
}

JunctionSimilarity::Bands JunctionSimilarity::BandsOf(int index_a, int index_b) const {
  Bands bands;
  if (!has_geometry_ || !options_.use_pose_band) {
    bands.in_image1 = bands.in_image2 = options_.max_epipolar_distance_px;
    return bands;
  }
  const double sigma_e = PoseSigmaE(index_a, index_b);
  bands.in_image2 = PoseBand(sigma_e, side_a_.location_line_norm[index_a]);
  bands.in_image1 = PoseBand(sigma_e, side_b_.location_line_norm[index_b]);
  return bands;
}

// Residual e = x2^T F x1 and its pose sigma; d' = |e| / |F x1|_xy, d = |e| / |F^T x2|_xy.
double JunctionSimilarity::PoseSigmaE(int index_a, int index_b) const {
  return (side_a_.deviation[index_a].transpose() * side_b_.location[index_b].homogeneous()).norm();
}

// The band of sigma_e over the norm of an epipolar line's (a, b).
double JunctionSimilarity::PoseBand(double sigma_e, double line_norm) const {
  return EpipolarBand(line_norm > 0 ? sigma_e / line_norm : std::numeric_limits<double>::infinity(),
                      options_.location_sigma_px, options_.band_sigmas);
}

std::optional<double> JunctionSimilarity::M(int index_a, int index_b, int shift) const {
  return M(index_a, index_b, shift, BandsOf(index_a, index_b));
}

// H(s) H'(s) of one segment pair of eq. (32): H from image 1 to image 2 (F), H' back (F^T, the
// roles swapped); nullopt where (17) rejects the pair.
std::optional<double> JunctionSimilarity::SegmentPairSupport(int ia, int ib, const Bands& bands) const {
  const OrientedSegment& segment = side_a_.segments[ia];
  const OrientedSegment& partner = side_b_.segments[ib];
  const std::optional<double> h = EndpointSupport(
      TransferSegment(segment, side_a_.epipolar[ia], partner, options_.parallel_tolerance_px, bands.in_image2),
      options_.endpoint_model);
  if (!h) return std::nullopt;
  const std::optional<double> h_prime = EndpointSupport(
      TransferSegment(partner, side_b_.epipolar[ib], segment, options_.parallel_tolerance_px, bands.in_image1),
      options_.endpoint_model);
  if (!h_prime) return std::nullopt;
  return *h * *h_prime;
}

std::optional<double> JunctionSimilarity::M(int index_a, int index_b, int shift, const Bands& bands) const {
  const int n = side_a_.count[index_a];
  CHECK_EQ(n, side_b_.count[index_b]);
  const int first_a = side_a_.first[index_a];
  const int first_b = side_b_.first[index_b];
  // The physical constraints first: they are cheap and reject most shifts.
  const Eigen::Vector2d* directions_a = &side_a_.directions[first_a];
  const Eigen::Vector2d* directions_b = &side_b_.directions[first_b];
  if (!IsSmallRotation(directions_a, directions_b, n, shift) ||
      !KeepsCyclicOrder(directions_a, directions_b, n, shift, min_sin_)) {
    return std::nullopt;
  }
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const int ia = first_a + i;
    const int ib = first_b + (i + shift) % n;
    const std::optional<double> support = SegmentPairSupport(ia, ib, bands);
    if (!support) return std::nullopt;
    sum += *support;
  }
  return sum / n;
}

bool JunctionSimilarity::PassesCheirality(int index_a, int index_b) const {
  if (!has_geometry_ || !options_.use_cheirality) return true;
  // sfm::PassesCheirality with each location's part computed once.
  const Eigen::Vector2d& x1 = side_a_.location[index_a];
  const Eigen::Vector2d& x2 = side_b_.location[index_b];
  const ParallaxFrame& forward = ParallaxOf(side_a_, geometry_, index_a);
  if (forward.tested && (x2 - forward.v).dot(forward.direction) < -side_a_.parallax_tolerance[index_a]) return false;
  const ParallaxFrame& backward = ParallaxOf(side_b_, inverse_geometry_, index_b);
  return !(backward.tested && (x1 - backward.v).dot(backward.direction) < -side_b_.parallax_tolerance[index_b]);
}

const ParallaxFrame& JunctionSimilarity::ParallaxOf(const Side& side, const PairGeometry& pose,
                                                    int index) const {
  if (!side.parallax_known[index]) {
    side.parallax[index] = ParallaxFrameOf(pose, side.location[index]);
    side.parallax_tolerance[index] =
        EpipolarBand(side.parallax[index].sigma, options_.location_sigma_px, options_.band_sigmas);
    side.parallax_known[index] = 1;
  }
  return side.parallax[index];
}

bool JunctionSimilarity::LocationsAgree(int index_a, int index_b, Bands* bands, double* d, double* d_prime) const {
  // d' of p'0 from the line of p0, d of p0 from the line of p'0 (lines normalised): the cheap test
  // that rejects nearly every pair.
  *d_prime = DistanceToLine(side_a_.location_line[index_a], side_b_.location[index_b]);
  if (has_geometry_ && options_.use_pose_band) {
    // Cheap rejection first, with the band of the largest sigma_d' over b's locations.
    if (!(*d_prime <= side_a_.deviation_bound[index_a])) return false;
  }
  if (has_geometry_ && options_.use_pose_band) {
    // BandsOf, with the band in image 1 computed only for a pair whose d' passes.
    const double sigma_e = PoseSigmaE(index_a, index_b);
    bands->in_image2 = PoseBand(sigma_e, side_a_.location_line_norm[index_a]);
    if (!(*d_prime <= bands->in_image2)) return false;
    bands->in_image1 = PoseBand(sigma_e, side_b_.location_line_norm[index_b]);
  } else {
    *bands = BandsOf(index_a, index_b);
    if (!(*d_prime <= bands->in_image2)) return false;
  }
  *d = DistanceToLine(side_b_.location_line[index_b], side_a_.location[index_a]);
  if (!(*d <= bands->in_image1)) return false;
  return PassesCheirality(index_a, index_b);
}

PairSimilarity JunctionSimilarity::Rho(int index_a, int index_b) const {
  PairSimilarity result;
  const int n = side_a_.count[index_a];
  if (n != side_b_.count[index_b] || n == 0) return result;
  Bands bands;
  double d = 0, d_prime = 0;
  if (!LocationsAgree(index_a, index_b, &bands, &d, &d_prime)) return result;
  double rho2 = 0;
  for (int shift = 0; shift < n; ++shift) {
    const std::optional<double> m = M(index_a, index_b, shift, bands);
    if (m && (result.shift < 0 || *m > rho2)) {
      rho2 = *m;
      result.shift = shift;
    }
  }
  if (result.shift < 0) return result;
  // With a fixed R this is (31) as written; with per-pair bands the same in units of each band.
  const double rho1 = has_geometry_ && options_.use_pose_band ? Rho1(d / bands.in_image1, d_prime / bands.in_image2, 1.0, options_.rho1_kind)
                                : Rho1(d, d_prime, options_.max_epipolar_distance_px, options_.rho1_kind);
  result.rho = 0.5 * (rho1 + rho2);
  return result;
}

std::optional<double> JunctionSimilarity::SubsetSupport(int index_a, int index_b, const int* segments_a,
                                                        const int* segments_b, int n, int shift,
                                                        const Bands& bands) const {
  constexpr int kMax = 16;
  CHECK_LE(n, kMax);
  Eigen::Vector2d directions_a[kMax];
  Eigen::Vector2d directions_b[kMax];
  const int first_a = side_a_.first[index_a];
  const int first_b = side_b_.first[index_b];
  for (int i = 0; i < n; ++i) {
    directions_a[i] = side_a_.directions[first_a + segments_a[i]];
    directions_b[i] = side_b_.directions[first_b + segments_b[i]];
  }
  // (36) on the subsets: removing a segment from a clockwise junction leaves a clockwise junction,
  // so the test applies to the k kept segments as to any junction of k.
  if (!IsSmallRotation(directions_a, directions_b, n, shift) ||
      !KeepsCyclicOrder(directions_a, directions_b, n, shift, min_sin_)) {
    return std::nullopt;
  }
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const int ia = first_a + segments_a[i];
    const int ib = first_b + segments_b[(i + shift) % n];
    const std::optional<double> support = SegmentPairSupport(ia, ib, bands);
    if (!support) return std::nullopt;
    sum += *support;
  }
  return sum;
}

PairSimilarity JunctionSimilarity::PartialRho(int index_a, int index_b) const {
  PairSimilarity result;
  const int n_a = side_a_.count[index_a];
  const int n_b = side_b_.count[index_b];
  const int k = std::min(n_a, n_b);
  // One segment of common support is no junction correspondence (its turn and (36) are gone).
  if (std::abs(n_a - n_b) != 1 || k < 2 || k + 1 > 16) return result;
  Bands bands;
  double d = 0, d_prime = 0;
  if (!LocationsAgree(index_a, index_b, &bands, &d, &d_prime)) return result;
  int all[16];
  int subset[16];
  for (int i = 0; i < k + 1; ++i) all[i] = i;
  const bool a_larger = n_a > n_b;
  const Side& larger = a_larger ? side_a_ : side_b_;
  const int first_larger = larger.first[a_larger ? index_a : index_b];
  const Eigen::Vector2d* larger_directions = larger.directions.data() + first_larger;
  const int* larger_lines = larger.line_segments.data() + first_larger;
  const Side& smaller = a_larger ? side_b_ : side_a_;
  const int first_smaller = smaller.first[a_larger ? index_b : index_a];
  const int smaller_lines_through =
      LinesThrough(smaller.directions.data() + first_smaller, smaller.line_segments.data() + first_smaller,
                   all, k, min_sin_);
  double best = 0;
  for (int missing = 0; missing <= k; ++missing) {
    // Partial correspondence stands for a junction segment that detection missed in one frame.
    // The larger junction's segments without `missing`, in their (clockwise) order.
    for (int i = 0, j = 0; i <= k; ++i) {
      if (i != missing) subset[j++] = i;
    }
    // Without its missed segment the larger junction is what detection reads in the other frame,
    // so the kept segments must have the smaller junction's lines through the location: a T
    // without its stem is a straight line, not an L (and an X without a half-line a T, not a Y).
    if (LinesThrough(larger_directions, larger_lines, subset, k, min_sin_) != smaller_lines_through) continue;
    for (int shift = 0; shift < k; ++shift) {
      const std::optional<double> sum = a_larger ? SubsetSupport(index_a, index_b, subset, all, k, shift, bands)
                                                 : SubsetSupport(index_a, index_b, all, subset, k, shift, bands);
      if (!sum) continue;
      // The missing segment's H H' is 0: the mean over the k + 1 segments of the union.
      const double m = *sum / (k + 1);
      if (result.shift < 0 || m > best) {
        best = m;
        result.shift = shift;
        result.missing_a = a_larger ? missing : -1;
        result.missing_b = a_larger ? -1 : missing;
      }
    }
  }
  if (result.shift < 0) return result;
  const double rho1 = has_geometry_ && options_.use_pose_band ? Rho1(d / bands.in_image1, d_prime / bands.in_image2, 1.0, options_.rho1_kind)
                                : Rho1(d, d_prime, options_.max_epipolar_distance_px, options_.rho1_kind);
  result.rho = 0.5 * (rho1 + best);
  return result;
}

PairSimilarity JunctionSimilarity::OneCommonRho(int index_a, int index_b) const {
  PairSimilarity result;
  if (side_a_.count[index_a] != 2 || side_b_.count[index_b] != 2) return result;
  Bands bands;
  double d = 0, d_prime = 0;
  if (!LocationsAgree(index_a, index_b, &bands, &d, &d_prime)) return result;
  const int first_a = side_a_.first[index_a];
  const int first_b = side_b_.first[index_b];
  double best = 0;
  for (int sa = 0; sa < 2; ++sa) {
    for (int sb = 0; sb < 2; ++sb) {
      // (37) on the shared pair: one segment seen in both frames turns by less than 90 degrees.
      const Eigen::Vector2d& da = side_a_.directions[first_a + sa];
      const Eigen::Vector2d& db = side_b_.directions[first_b + sb];
      if (!(da.dot(db) > 0)) continue;
      const std::optional<double> support = SegmentPairSupport(first_a + sa, first_b + sb, bands);
      if (!support) continue;
      // The mean over the union's three segments, the two unshared ones' terms 0.
      const double m = *support / 3;
      if (result.shift < 0 || m > best) {
        best = m;
        result.shift = 0;
        result.missing_a = 1 - sa;
        result.missing_b = 1 - sb;
      }
    }
  }
  if (result.shift < 0) return result;
  const double rho1 = has_geometry_ && options_.use_pose_band
                          ? Rho1(d / bands.in_image1, d_prime / bands.in_image2, 1.0, options_.rho1_kind)
                          : Rho1(d, d_prime, options_.max_epipolar_distance_px, options_.rho1_kind);
  result.rho = 0.5 * (rho1 + best);
  return result;
}

}  // namespace sfm

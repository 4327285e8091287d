#include "frontend/matching/junction_similarity.h"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <glog/logging.h>

#include "frontend/matching/endpoint_support.h"
#include "frontend/matching/physical_constraints.h"

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

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
    // A location at the epipole has no epipolar line: no distance is within R of it.
    side.location_line.push_back(norm > 0 ? Eigen::Vector3d(line / norm)
                                          : Eigen::Vector3d(0, 0, std::numeric_limits<double>::infinity()));
    for (const JunctionSegment& segment : junction.segments) {
      side.segments.push_back(OrientedSegment::FromPoints(junction.location, segment.end));
      side.directions.push_back(side.segments.back().direction);
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
      side_b_(MakeSide(b, F.transpose())) {}

std::optional<double> JunctionSimilarity::M(int index_a, int index_b, int shift) const {
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
  const double R = options_.max_epipolar_distance_px;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const int ia = first_a + i;
    const int ib = first_b + (i + shift) % n;
    const OrientedSegment& segment = side_a_.segments[ia];
    const OrientedSegment& partner = side_b_.segments[ib];
    const std::optional<double> h = EndpointSupport(
        TransferSegment(segment, side_a_.epipolar[ia], partner, options_.parallel_tolerance_px, R),
        options_.endpoint_model);
    if (!h) return std::nullopt;
    // H': from image 2 to image 1, F^T, the roles swapped.
    const std::optional<double> h_prime = EndpointSupport(
        TransferSegment(partner, side_b_.epipolar[ib], segment, options_.parallel_tolerance_px, R),
        options_.endpoint_model);
    if (!h_prime) return std::nullopt;
    sum += *h * *h_prime;
  }
  return sum / n;
}

PairSimilarity JunctionSimilarity::Rho(int index_a, int index_b) const {
  PairSimilarity result;
  const int n = side_a_.count[index_a];
  if (n != side_b_.count[index_b] || n == 0) return result;
  // d' of p'0 from the line of p0, d of p0 from the line of p'0 (lines normalised): the cheap test
  // that rejects nearly every pair.
  const double R = options_.max_epipolar_distance_px;
  const double d_prime = std::abs(side_a_.location_line[index_a].dot(side_b_.location[index_b].homogeneous()));
  if (!(d_prime <= R)) return result;
  const double d = std::abs(side_b_.location_line[index_b].dot(side_a_.location[index_a].homogeneous()));
  if (!(d <= R)) return result;
  double rho2 = 0;
  for (int shift = 0; shift < n; ++shift) {
    const std::optional<double> m = M(index_a, index_b, shift);
    if (m && (result.shift < 0 || *m > rho2)) {
      rho2 = *m;
      result.shift = shift;
    }
  }
  if (result.shift < 0) return result;
  result.rho = 0.5 * (Rho1(d, d_prime, R, options_.rho1_kind) + rho2);
  return result;
}

}  // namespace sfm

#include "frontend/matching/epipolar_transfer.h"

#include <cmath>

#include <Eigen/Geometry>
#include <glog/logging.h>

namespace sfm {

OrientedSegment OrientedSegment::FromPoints(const Eigen::Vector2d& origin, const Eigen::Vector2d& end) {
  OrientedSegment segment;
  segment.origin = origin;
  segment.end = end;
  segment.length = (end - origin).norm();
  CHECK_GT(segment.length, 0) << "junction segment of zero length at " << origin.transpose();
  segment.direction = (end - origin) / segment.length;
  return segment;
}

EndpointEpipolar MakeEndpointEpipolar(const Eigen::Matrix3d& F, const OrientedSegment& segment) {
  const Eigen::Vector3d line = F * segment.end.homogeneous();
  const Eigen::Vector3d derivative = F.leftCols<2>() * segment.direction;
  EndpointEpipolar epipolar;
  epipolar.a = line.head<2>();
  epipolar.b = line.z();
  epipolar.u = derivative.head<2>();
  epipolar.v = derivative.z();
  return epipolar;
}

SegmentTransfer TransferSegment(const OrientedSegment& segment, const EndpointEpipolar& epipolar,
                                const OrientedSegment& partner, double parallel_tolerance_px,
                                double collinear_tolerance_px) {
  const Eigen::Vector2d& a = epipolar.a;
  const double a_dot_n = a.dot(partner.direction);
  // Signed distance of p'_i from the epipolar line of p_i, times |a|.
  const double a_dot_end = a.dot(partner.end) + epipolar.b;
  const double a_norm = a.norm();
  SegmentTransfer transfer;
  // |a.n'| L' / |a| is how much the line's distance from the partner changes along the partner.
  // (a = 0 when p_i is the epipole: every line there is epipolar, so the pair counts as collinear
  // when b = 0 too.)
  if (std::abs(a_dot_n) * partner.length <= parallel_tolerance_px * a_norm) {
    if (std::abs(a_dot_end) <= collinear_tolerance_px * a_norm) {
      transfer.kind = SegmentTransfer::Case::kParallelCollinear;
      transfer.D = -partner.length / segment.length;
    } else {
      transfer.kind = SegmentTransfer::Case::kParallelApart;
    }
    return transfer;
  }
  transfer.ds = -a_dot_end / a_dot_n;
  const Eigen::Vector2d p_e = partner.end + transfer.ds * partner.direction;
  transfer.K = epipolar.u.dot(partner.direction) / a_dot_n;
  transfer.D = (epipolar.u.dot(p_e) + epipolar.v) / a_dot_n;
  return transfer;
}

double TOfS(double s, double K, double D) { return s / (s * K - D); }

double DtDs(double s, double K, double D) {
  const double x = s * K - D;
  return -D / (x * x);
}

bool SatisfiesNecessaryCondition(double s, double K, double D) { return D < 0 && s * K - D > 0; }

double G(double s, double K, double D, const EndpointModel& model) {
  if (!SatisfiesNecessaryCondition(s, K, D)) return 0;
  const double x = s * K - D;
  if (s >= 0) {
    if (model.lambda < -2 * K) return -std::exp(-model.lambda * s) / D;
    // -D/x^2 * exp(..) in logs: near the vanishing point x -> 0 and the factors overflow apart.
    return std::exp(std::log(-D) - 2 * std::log(x) - model.lambda * s / x);
  }
  if (model.mu < 2 * K) return -std::exp(model.mu * s) / D;
  return std::exp(std::log(-D) - 2 * std::log(x) + model.mu * s / x);
}

}  // namespace sfm

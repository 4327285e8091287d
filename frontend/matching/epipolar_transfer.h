// Propagation of a junction segment's end-point uncertainty to the epipolar line (paper section
// 3.2, eq. 8-19).
//
// Notation (docs/matching.md): junction segment p0 -> p_i with unit direction n_i in image 1, its
// hypothesised partner p'0 -> p'_i with direction n'_i in image 2, x2^T F x1 = 0.
//   t: detected minus true end-point p_i along n_i (eq. 8; t > 0: the detected segment is too long).
//   p'e: where the epipolar line of the detected p_i cuts the line p'0 p'_i.
//   p't: where the epipolar line of the true p_i cuts it; s = p'e - p't along n'_i (eq. 9).
//   ds: p'e - p'_i along n'_i (section 3.3).
#pragma once

#include <Eigen/Core>

#include "frontend/segments/endpoint_model.h"

namespace sfm {

// A junction segment as the matcher uses it: p0, the far end-point p_i, n_i of eq. (1), length.
struct OrientedSegment {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();     // p0, pixels
  Eigen::Vector2d end = Eigen::Vector2d::Zero();        // p_i, pixels
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // n_i = (p_i - p0) / |p_i - p0|
  double length = 0;                                     // |p_i - p0|, pixels

  // CHECKs that the end-point differs from p0.
  static OrientedSegment FromPoints(const Eigen::Vector2d& origin, const Eigen::Vector2d& end);
};

// [a; b] = F [p_i; 1] (the epipolar line of p_i) and [u; v] = F [n_i; 0] of eq. (12).
struct EndpointEpipolar {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  double b = 0;
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  double v = 0;
};
EndpointEpipolar MakeEndpointEpipolar(const Eigen::Matrix3d& F, const OrientedSegment& segment);

// The pairing of segment with partner reduced to the scalars of eq. (13)-(14) and ds.
struct SegmentTransfer {
  enum class Case {
    kGeneral,            // a.n'_i != 0: eq. (14)
    kParallelCollinear,  // epipolar line of p_i along the partner's line: no end-point information
    kParallelApart,      // epipolar line of p_i parallel to the partner's line, off it: g = 0
  };
  Case kind = Case::kGeneral;
  double K = 0;   // eq. (14): (u.n'_i) / (a.n'_i), 1/pixels
  double D = 0;   // eq. (14): (u.p'e + v) / (a.n'_i), unitless (-D is ds/dt at s = 0)
  double ds = 0;  // -(a.p'_i + b) / (a.n'_i): signed distance from p'_i to p'e along n'_i, pixels
};

// Eq. (12)-(14) for segment (image 1) and partner (image 2), with epipolar = MakeEndpointEpipolar(F,
// segment). Parallel case (section 3.2, last paragraph): the line of p_i counts as parallel to
// the partner when over the partner's length it departs from the partner's line by at most
// parallel_tolerance_px, and as collinear when p'_i is then within collinear_tolerance_px of it.
// The paper takes g = -1/D there, but D is 0/0 (both segments lie in one epipolar plane and F
// fixes no scale along them); we use -1/D = dt/ds ~ |p_i - p0| / |p'_i - p'0|, the segments' own
// length ratio, with p'e = p't = p'_i (s = ds = 0), so H * H' = 1 for such a pair.
SegmentTransfer TransferSegment(const OrientedSegment& segment, const EndpointEpipolar& epipolar,
                                const OrientedSegment& partner, double parallel_tolerance_px,
                                double collinear_tolerance_px);

// Eq. (15): t = s / (sK - D).
double TOfS(double s, double K, double D);
// Eq. (16): dt/ds = -D / (sK - D)^2.
double DtDs(double s, double K, double D);
// Eq. (17), the necessary condition for two images of one 3D line: D < 0 and sK - D > 0.
bool SatisfiesNecessaryCondition(double s, double K, double D);

// Eq. (19): density of s, g(s) = f(t) |dt/ds| with t from (15), falling back to
// -(1/D) exp(-lambda s) (s >= 0, lambda < -2K) or -(1/D) exp(mu s) (s < 0, mu < 2K) where the model
// would not make g decrease away from s = 0. 0 where (17) fails at s. 1/pixels.
double G(double s, double K, double D, const EndpointModel& model);

}  // namespace sfm

// Propagation of the end-point uncertainty to the epipolar constraint (paper section 3.3, eq.
// 20-30): H(p_i, p'_i), how well the detected end-points p_i and p'_i agree with two images of one
// 3D line end. Notation of epipolar_transfer.h.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "frontend/matching/epipolar_transfer.h"
#include "frontend/segments/endpoint_model.h"

namespace sfm {

// Eq. (20)-(22): h(s) = f(s - ds) g(s), the density of the true end-point p't sitting at s when
// the partner's end-point was detected at ds; f of eq. (5) for the partner's end-point, g of (19).
// Defined for every s (0 where (17) fails); the maximum lies in [0, ds] or [ds, 0]. 1/pixels.
double HOfS(double s, double K, double D, double ds, const EndpointModel& model);

// Which closed form gave the maximum of h (the paper's case and, for the monotone cases, the end
// of the interval where it lies).
enum class HMaxBranch {
  kEq23AtZero,      // K = 0, 0 <= s <= ds, mu <= -lambda/D: h(0)
  kEq23AtDs,        // K = 0, 0 <= s <= ds, mu > -lambda/D: h(ds)
  kEq24AtDs,        // K = 0, ds <= s < 0, lambda > -mu/D: h(ds)
  kEq24AtZero,      // K = 0, ds <= s < 0, lambda <= -mu/D: h(0)
  kEq25AtZero,      // K != 0, 0 <= s <= ds, lambda < -2K, mu <= lambda: h(0)
  kEq25AtDs,        // K != 0, 0 <= s <= ds, lambda < -2K, mu > lambda: h(ds)
  kEq27Stationary,  // K < 0, 0 <= s <= ds, lambda >= -2K, s_m of (26) in the interval: h(s_m)
  kEq27Ends,        // K != 0, 0 <= s <= ds, lambda >= -2K, otherwise: max(h(0), h(ds))
  kEq28AtZero,      // K != 0, ds <= s < 0, mu < 2K, mu >= lambda: h(0)
  kEq28AtDs,        // K != 0, ds <= s < 0, mu < 2K, mu < lambda: h(ds)
  kEq29Stationary,  // K > 0, ds <= s < 0, mu >= 2K, s_m of (30) in the interval: h(s_m)
  kEq29Ends,        // K != 0, ds <= s < 0, mu >= 2K, otherwise: max(h(0), h(ds))
};
constexpr int kNumHMaxBranches = 12;
const char* HMaxBranchName(HMaxBranch branch);

struct HMaximum {
  double value = 0;  // max of h over the interval, 1/pixels
  HMaxBranch branch = HMaxBranch::kEq23AtZero;
};

// Eq. (23)-(30): max of h(s) over 0 <= s <= ds (ds >= 0) or ds <= s <= 0 (ds < 0), in closed form.
// Requires (17) on the whole interval: D < 0 and ds K - D > 0 (CHECKed).
HMaximum MaxH(double K, double D, double ds, const EndpointModel& model);

// Eq. (21) with Delta s = 1 pixel: H = max_s h(s) for a segment pairing. nullopt when the pairing
// fails the necessary condition (17) somewhere on [0, ds] (D >= 0, or p'_i and p'e on opposite
// sides of the partner line's vanishing point); 0 for an epipolar line parallel to the partner and
// off it; -1/D for one along it (see TransferSegment).
std::optional<double> EndpointSupport(const SegmentTransfer& transfer, const EndpointModel& model);

// H(p_i, p'_i) of segment (image 1) against partner (image 2), from image 1 to image 2.
std::optional<double> H(const Eigen::Matrix3d& F, const OrientedSegment& segment,
                        const OrientedSegment& partner, const EndpointModel& model,
                        double parallel_tolerance_px, double collinear_tolerance_px);
// H'(p_i, p'_i): the same from image 2 to image 1, i.e. H with F^T and the roles swapped.
std::optional<double> HPrime(const Eigen::Matrix3d& F, const OrientedSegment& segment,
                             const OrientedSegment& partner, const EndpointModel& model,
                             double parallel_tolerance_px, double collinear_tolerance_px);

}  // namespace sfm

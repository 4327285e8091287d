#include "frontend/matching/endpoint_support.h"

#include <algorithm>
#include <cmath>

#include <glog/logging.h>

namespace sfm {

double HOfS(double s, double K, double D, double ds, const EndpointModel& model) {
  return model.F(s - ds) * G(s, K, D, model);
}

const char* HMaxBranchName(HMaxBranch branch) {
  switch (branch) {
    case HMaxBranch::kEq23AtZero: return "(23) h(0)";
    case HMaxBranch::kEq23AtDs: return "(23) h(ds)";
    case HMaxBranch::kEq24AtDs: return "(24) h(ds)";
    case HMaxBranch::kEq24AtZero: return "(24) h(0)";
    case HMaxBranch::kEq25AtZero: return "(25) h(0)";
    case HMaxBranch::kEq25AtDs: return "(25) h(ds)";
    case HMaxBranch::kEq27Stationary: return "(26)-(27) h(sm)";
    case HMaxBranch::kEq27Ends: return "(27) max(h(0), h(ds))";
    case HMaxBranch::kEq28AtZero: return "(28) h(0)";
    case HMaxBranch::kEq28AtDs: return "(28) h(ds)";
    case HMaxBranch::kEq29Stationary: return "(29)-(30) h(sm)";
    case HMaxBranch::kEq29Ends: return "(29) max(h(0), h(ds))";
  }
  return "?";
}

HMaximum MaxH(double K, double D, double ds, const EndpointModel& model) {
  CHECK(SatisfiesNecessaryCondition(ds, K, D)) << "K " << K << " D " << D << " ds " << ds;
  const double lambda = model.lambda;
  const double mu = model.mu;
  const double h0 = -1 / D;  // the common factor: h(0) with ds = 0, g(0) = -1/D
  auto h = [&](double s) { return HOfS(s, K, D, ds, model); };
  // The stationary points (26) and (30) solve a quadratic in x = sK - D > 0; its positive root is
  // written here so that it does not cancel, then s_m = (x + D) / K.
  const double c = -lambda * mu * D;  // > 0
  const double r = std::sqrt(K * K + c);
  if (ds >= 0) {
    if (K == 0) {  // (23): h is exp-linear in s.
      if (mu <= -lambda / D) return {h0 * std::exp(-mu * ds), HMaxBranch::kEq23AtZero};
      return {h0 * std::exp(lambda * ds / D), HMaxBranch::kEq23AtDs};
    }
    if (lambda < -2 * K) {  // (25): g fell back to -(1/D) exp(-lambda s).
      if (mu <= lambda) return {h0 * std::exp(-mu * ds), HMaxBranch::kEq25AtZero};
      return {h0 * std::exp(-lambda * ds), HMaxBranch::kEq25AtDs};
    }
    // (26)-(27): mu x^2 - 2K x + lambda D = 0; a maximum of h only for K < 0.
    if (K < 0) {
      const double x = c / (mu * (r - K));
      const double s_m = (x + D) / K;
      if (s_m >= 0 && s_m <= ds) return {h(s_m), HMaxBranch::kEq27Stationary};
    }
    return {std::max(h(0), h(ds)), HMaxBranch::kEq27Ends};
  }
  if (K == 0) {  // (24)
    if (lambda <= -mu / D) return {h0 * std::exp(lambda * ds), HMaxBranch::kEq24AtZero};
    return {h0 * std::exp(-mu * ds / D), HMaxBranch::kEq24AtDs};
  }
  if (mu < 2 * K) {  // (28): g fell back to -(1/D) exp(mu s).
    if (mu >= lambda) return {h0 * std::exp(lambda * ds), HMaxBranch::kEq28AtZero};
    return {h0 * std::exp(mu * ds), HMaxBranch::kEq28AtDs};
  }
  // (29)-(30): lambda x^2 + 2K x + mu D = 0; a maximum of h only for K > 0.
  if (K > 0) {
    const double x = c / (lambda * (r + K));
    const double s_m = (x + D) / K;
    if (s_m >= ds && s_m <= 0) return {h(s_m), HMaxBranch::kEq29Stationary};
  }
  return {std::max(h(0), h(ds)), HMaxBranch::kEq29Ends};
}

std::optional<double> EndpointSupport(const SegmentTransfer& transfer, const EndpointModel& model) {
  switch (transfer.kind) {
    case SegmentTransfer::Case::kParallelApart:
      return 0.0;
    case SegmentTransfer::Case::kParallelCollinear:
      return -1 / transfer.D;
    case SegmentTransfer::Case::kGeneral:
      break;
  }
  // (17) on [0, ds]: sK - D is linear in s and equals -D at s = 0, so checking both ends suffices.
  if (!SatisfiesNecessaryCondition(transfer.ds, transfer.K, transfer.D) || !std::isfinite(transfer.ds)) {
    return std::nullopt;
  }
  return MaxH(transfer.K, transfer.D, transfer.ds, model).value;  // (21), Delta s = 1
}

std::optional<double> H(const Eigen::Matrix3d& F, const OrientedSegment& segment,
                        const OrientedSegment& partner, const EndpointModel& model,
                        double parallel_tolerance_px, double collinear_tolerance_px) {
  const SegmentTransfer transfer = TransferSegment(segment, MakeEndpointEpipolar(F, segment), partner,
                                                   parallel_tolerance_px, collinear_tolerance_px);
  return EndpointSupport(transfer, model);
}

std::optional<double> HPrime(const Eigen::Matrix3d& F, const OrientedSegment& segment,
                             const OrientedSegment& partner, const EndpointModel& model,
                             double parallel_tolerance_px, double collinear_tolerance_px) {
  return H(F.transpose(), partner, segment, model, parallel_tolerance_px, collinear_tolerance_px);
}

}  // namespace sfm

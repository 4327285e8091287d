// Section 3.2 on a hand-built F and segments: every number below was worked out by hand (in
// fractions) from eq. (12)-(19).
#include "frontend/matching/epipolar_transfer.h"

#include <cmath>

#include <gtest/gtest.h>

#include "frontend/matching/endpoint_support.h"

namespace sfm {
namespace {

constexpr double kTolerance = 1e-12;

// Forward motion with K = I: F = [e_z]x, F x = (-y, x, 0); epipolar lines run through the origin.
Eigen::Matrix3d ForwardF() {
  Eigen::Matrix3d F;
  F << 0, -1, 0, 1, 0, 0, 0, 0, 0;
  return F;
}

// Image 1: p0 = (0, 10) -> p_i = (4, 10), n = (1, 0). Image 2: p'0 = (0, 20) -> p'_i = (6, 28),
// n' = (0.6, 0.8).
// By hand: a = (-10, 4), b = 0, u = (0, 1), v = 0, a.n' = -2.8; the line y = 2.5 x of p_i cuts the
// partner at p'e = (120/7, 300/7), so ds = 130/7, K = 0.8 / -2.8 = -2/7, D = (300/7) / -2.8 = -750/49.
OrientedSegment Segment() { return OrientedSegment::FromPoints({0, 10}, {4, 10}); }
OrientedSegment Partner() { return OrientedSegment::FromPoints({0, 20}, {6, 28}); }

EndpointModel Model(double lambda, double mu) {
  EndpointModel model;
  model.lambda = lambda;
  model.mu = mu;
  return model;
}

TEST(EpipolarTransferTest, HandComputedKDAndDs) {
  const EndpointEpipolar epipolar = MakeEndpointEpipolar(ForwardF(), Segment());
  EXPECT_NEAR(epipolar.a.x(), -10, kTolerance);
  EXPECT_NEAR(epipolar.a.y(), 4, kTolerance);
  EXPECT_NEAR(epipolar.b, 0, kTolerance);
  EXPECT_NEAR(epipolar.u.x(), 0, kTolerance);
  EXPECT_NEAR(epipolar.u.y(), 1, kTolerance);
  EXPECT_NEAR(epipolar.v, 0, kTolerance);
  const SegmentTransfer transfer = TransferSegment(Segment(), epipolar, Partner(), 1.0, 10.0);
  ASSERT_EQ(transfer.kind, SegmentTransfer::Case::kGeneral);
  EXPECT_NEAR(transfer.K, -2.0 / 7, kTolerance);
  EXPECT_NEAR(transfer.D, -750.0 / 49, kTolerance);
  EXPECT_NEAR(transfer.ds, 130.0 / 7, kTolerance);
  // (17) over [0, ds]: D < 0, and ds K - D = -260/49 + 750/49 = 10.
  EXPECT_TRUE(SatisfiesNecessaryCondition(transfer.ds, transfer.K, transfer.D));
  EXPECT_NEAR(transfer.ds * transfer.K - transfer.D, 10, kTolerance);
}

TEST(EpipolarTransferTest, HandComputedTAndG) {
  const double K = -2.0 / 7, D = -750.0 / 49;
  // s = 7: sK - D = 652/49, t = 343/652 (15), dt/ds = 36750/425104 (16).
  EXPECT_NEAR(TOfS(7, K, D), 343.0 / 652, kTolerance);
  EXPECT_NEAR(DtDs(7, K, D), 36750.0 / 425104, kTolerance);
  // s = -7: sK - D = 848/49, t = -343/848, dt/ds = 36750/719104.
  EXPECT_NEAR(TOfS(-7, K, D), -343.0 / 848, kTolerance);
  EXPECT_NEAR(DtDs(-7, K, D), 36750.0 / 719104, kTolerance);
  // (19) with lambda = 1 >= -2K = 4/7 and mu = 0.2 >= 2K: g = f(t) dt/ds on both sides.
  const EndpointModel model = Model(1.0, 0.2);
  EXPECT_NEAR(G(7, K, D, model), 36750.0 / 425104 * std::exp(-343.0 / 652), kTolerance);
  EXPECT_NEAR(G(-7, K, D, model), 36750.0 / 719104 * std::exp(-0.2 * 343.0 / 848), kTolerance);
  EXPECT_NEAR(G(0, K, D, model), 49.0 / 750, kTolerance);  // -1/D
  // lambda = 0.5 < 4/7: g would not decrease away from 0, so g = -(1/D) exp(-lambda s).
  EXPECT_NEAR(G(7, K, D, Model(0.5, 0.2)), 49.0 / 750 * std::exp(-3.5), kTolerance);
  // Outside the domain (s >= D/K = 375/7) (17) fails and g = 0.
  EXPECT_FALSE(SatisfiesNecessaryCondition(60, K, D));
  EXPECT_EQ(G(60, K, D, model), 0);
}

TEST(EpipolarTransferTest, HandComputedReverseDirectionAndMuFallback) {
  // H' of the same pair: F^T, the partner as the segment. By hand: a = F^T (6, 28, 1) = (28, -6),
  // u = F^T (0.6, 0.8, 0) = (0.8, -0.6), a.n = 28; the line y = 14x/3 of p'_i cuts y = 10 at
  // x = 15/7, so ds = 15/7 - 4 = -13/7, K = 0.8/28 = 1/35, D = (12/7 - 6)/28 = -15/98.
  const OrientedSegment segment = Partner(), partner = Segment();
  const SegmentTransfer transfer = TransferSegment(
      segment, MakeEndpointEpipolar(ForwardF().transpose(), segment), partner, 1.0, 10.0);
  ASSERT_EQ(transfer.kind, SegmentTransfer::Case::kGeneral);
  EXPECT_NEAR(transfer.K, 1.0 / 35, kTolerance);
  EXPECT_NEAR(transfer.D, -15.0 / 98, kTolerance);
  EXPECT_NEAR(transfer.ds, -13.0 / 7, kTolerance);
  // mu = 0.05 < 2K = 2/35: for s < 0, g = -(1/D) exp(mu s).
  EXPECT_NEAR(G(-1, transfer.K, transfer.D, Model(1.0, 0.05)), 98.0 / 15 * std::exp(-0.05), kTolerance);
  // mu = 0.2 >= 2K: g = f(t) dt/ds with t = -1/(-1/35 + 15/98) = -490/61, dt/ds = (15/98)/(61/490)^2.
  const double t = -490.0 / 61, dtds = 15.0 / 98 / std::pow(61.0 / 490, 2);
  EXPECT_NEAR(TOfS(-1, transfer.K, transfer.D), t, 1e-11);
  EXPECT_NEAR(G(-1, transfer.K, transfer.D, Model(1.0, 0.2)), dtds * std::exp(0.2 * t), 1e-11);
}

TEST(EpipolarTransferTest, HandComputedH) {
  // ds = 130/7 >= 0, K < 0, lambda >= -2K: (26)-(27). s_m = 375/7 + (1 - sqrt(38.5))/0.2 ~ 27.5 lies
  // beyond ds, so H = max(h(0), h(ds)); h(ds) = g(ds) = (750/49)/100 exp(-13/7) (t = ds/10) beats
  // h(0) = (49/750) exp(-0.2 * 130/7).
  const EndpointModel model = Model(1.0, 0.2);
  const std::optional<double> h = H(ForwardF(), Segment(), Partner(), model, 1.0, 10.0);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(*h, 15.0 / 98 * std::exp(-13.0 / 7), kTolerance);
  EXPECT_EQ(MaxH(-2.0 / 7, -750.0 / 49, 130.0 / 7, model).branch, HMaxBranch::kEq27Ends);
}

TEST(EpipolarTransferTest, NecessaryConditionRejectsAPartnerPointingTheWrongWay) {
  // The partner's line is the same, its segment runs the other way from p'0: a.n' and D change
  // sign, D = +750/49 > 0 fails (17) in both directions.
  const OrientedSegment reversed = OrientedSegment::FromPoints({0, 20}, {-6, 12});
  const EndpointModel model = Model(1.0, 0.2);
  const SegmentTransfer transfer =
      TransferSegment(Segment(), MakeEndpointEpipolar(ForwardF(), Segment()), reversed, 1.0, 10.0);
  EXPECT_NEAR(transfer.D, 750.0 / 49, kTolerance);
  EXPECT_FALSE(H(ForwardF(), Segment(), reversed, model, 1.0, 10.0).has_value());
  EXPECT_FALSE(HPrime(ForwardF(), Segment(), reversed, model, 1.0, 10.0).has_value());
  // The correct pairing passes both ways.
  EXPECT_TRUE(H(ForwardF(), Segment(), Partner(), model, 1.0, 10.0).has_value());
  EXPECT_TRUE(HPrime(ForwardF(), Segment(), Partner(), model, 1.0, 10.0).has_value());
}

TEST(EpipolarTransferTest, NecessaryConditionRejectsAnEndPointBeyondTheVanishingPoint) {
  // K > 0: the partner's line vanishes at s = D/K = -10; p'_i at ds = -20 lies beyond it.
  SegmentTransfer transfer;
  transfer.K = 0.1;
  transfer.D = -1;
  transfer.ds = -20;
  EXPECT_FALSE(EndpointSupport(transfer, Model(1.0, 0.2)).has_value());
  transfer.ds = -9;
  EXPECT_TRUE(EndpointSupport(transfer, Model(1.0, 0.2)).has_value());
}

TEST(EpipolarTransferTest, ParallelEpipolarLine) {
  // Rectified stereo, F = [e_x]x: epipolar lines are the rows y' = y.
  Eigen::Matrix3d F;
  F << 0, 0, 0, 0, 0, -1, 0, 1, 0;
  const EndpointModel model = Model(1.0, 0.2);
  const OrientedSegment segment = OrientedSegment::FromPoints({0, 10}, {20, 10});
  // Along the row of p_i (0.2 px off over 15 px: parallel within 1 px, collinear within R = 10):
  // H = -1/D = |p_i - p0| / |p'_i - p'0|, H' the inverse ratio.
  const OrientedSegment along = OrientedSegment::FromPoints({-5, 10}, {10, 10.2});
  const double ratio = 20 / std::hypot(15.0, 0.2);
  EXPECT_NEAR(*H(F, segment, along, model, 1.0, 10.0), ratio, kTolerance);
  EXPECT_NEAR(*HPrime(F, segment, along, model, 1.0, 10.0), 1 / ratio, kTolerance);
  // Parallel to the row but 20 px off it: g = 0.
  const OrientedSegment apart = OrientedSegment::FromPoints({-5, 30}, {10, 30});
  EXPECT_EQ(*H(F, segment, apart, model, 1.0, 10.0), 0);
  // K = 0 exactly in this geometry for a segment that is not along the rows (u = (0, 0)).
  const OrientedSegment diagonal = OrientedSegment::FromPoints({0, 0}, {10, 10});
  const OrientedSegment partner = OrientedSegment::FromPoints({-4, 0}, {7, 12});
  const SegmentTransfer transfer = TransferSegment(diagonal, MakeEndpointEpipolar(F, diagonal), partner, 1.0, 10.0);
  ASSERT_EQ(transfer.kind, SegmentTransfer::Case::kGeneral);
  EXPECT_EQ(transfer.K, 0);
  // By hand: a = (0, -1), b = 10, u = (0, 0), v = 1/sqrt(2); n' = (11, 12)/sqrt(265), a.n' =
  // -12/sqrt(265). The row y = 10 cuts the partner 2/12 of its length short of p'_i: ds =
  // -2 sqrt(265)/12; D = v / (a.n') = -sqrt(265) / (12 sqrt(2)), minus the local scale ds/dt.
  EXPECT_NEAR(transfer.ds, -2 * std::sqrt(265.0) / 12, kTolerance);
  EXPECT_NEAR(transfer.D, -std::sqrt(265.0) / 12 / std::sqrt(2.0), kTolerance);
}

}  // namespace
}  // namespace sfm

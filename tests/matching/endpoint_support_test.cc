// Section 3.3: the closed forms (23)-(30) of max h against a dense numeric maximisation in every
// branch, H non-increasing in |ds|, and H = H' on a set-up symmetric under swapping the images.
#include "frontend/matching/endpoint_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "tests/matching/synthetic_views.h"

namespace sfm {
namespace {

EndpointModel Model(double lambda, double mu) {
  EndpointModel model;
  model.lambda = lambda;
  model.mu = mu;
  return model;
}

// h(s) written straight from the four lines of (22), independently of the library's G: valid on
// 0 <= s <= ds (ds >= 0) or ds <= s <= 0 (ds < 0).
double H22(double s, double K, double D, double ds, double lambda, double mu) {
  const double x = s * K - D;
  if (ds >= 0) {
    if (lambda >= -2 * K) return -D / (x * x) * std::exp(mu * (s - ds) - lambda * s / x);
    return -1 / D * std::exp((mu - lambda) * s - mu * ds);
  }
  if (mu >= 2 * K) return -D / (x * x) * std::exp(-lambda * (s - ds) + mu * s / x);
  return -1 / D * std::exp((mu - lambda) * s + lambda * ds);
}

// Max of H22 over the interval: 20001 samples, then golden-section search around the best one.
double NumericMaxH(double K, double D, double ds, double lambda, double mu) {
  const double lo = std::min(0.0, ds), hi = std::max(0.0, ds);
  auto h = [&](double s) { return H22(s, K, D, ds, lambda, mu); };
  constexpr int kSamples = 20001;
  int best = 0;
  double best_value = -1;
  for (int k = 0; k < kSamples; ++k) {
    const double value = h(lo + (hi - lo) * k / (kSamples - 1));
    if (value > best_value) {
      best_value = value;
      best = k;
    }
  }
  double a = lo + (hi - lo) * std::max(best - 1, 0) / (kSamples - 1);
  double b = lo + (hi - lo) * std::min(best + 1, kSamples - 1) / (kSamples - 1);
  const double inverse_phi = (std::sqrt(5.0) - 1) / 2;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double c = b - inverse_phi * (b - a), d = a + inverse_phi * (b - a);
    if (h(c) > h(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return std::max(best_value, h(0.5 * (a + b)));
}

// Log-uniform in [lo, hi].
double LogUniform(double lo, double hi, std::mt19937* rng) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(*rng));
}

TEST(EndpointSupportTest, HOfSIsEquation22) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 1000; ++trial) {
    const double K = std::uniform_real_distribution<double>(-1, 1)(rng);
    const double D = -LogUniform(0.05, 20, &rng);
    const double ds = std::uniform_real_distribution<double>(-30, 30)(rng);
    const double lambda = LogUniform(0.02, 5, &rng), mu = LogUniform(0.02, 5, &rng);
    if (!SatisfiesNecessaryCondition(ds, K, D)) continue;
    const double s = ds * std::uniform_real_distribution<double>(0, 1)(rng);
    const double expected = H22(s, K, D, ds, lambda, mu);
    EXPECT_NEAR(HOfS(s, K, D, ds, Model(lambda, mu)), expected, 1e-12 * expected) << trial;
  }
}

TEST(EndpointSupportTest, ClosedFormMaximumAgreesWithNumericInEveryBranch) {
  std::mt19937 rng(2);
  constexpr int kPerBranch = 150;  // checks wanted in each branch
  std::array<int, kNumHMaxBranches> hits{};
  int ends_with_positive_K = 0, ends_with_negative_K = 0;  // (27)/(29) ends: both signs of K
  int checks = 0;
  for (int draw = 0; draw < 2000000; ++draw) {
    if (*std::min_element(hits.begin(), hits.end()) >= kPerBranch) break;
    const double lambda = LogUniform(0.02, 5, &rng), mu = LogUniform(0.02, 5, &rng);
    const double D = -LogUniform(0.05, 20, &rng);
    const int kind = std::uniform_int_distribution<int>(0, 3)(rng);
    double K = 0;
    if (kind == 1) K = LogUniform(1e-3, 3, &rng);
    if (kind == 2) K = -LogUniform(1e-3, 3, &rng);
    if (kind == 3) K = (std::uniform_int_distribution<int>(0, 1)(rng) ? 1 : -1) * LogUniform(1e-6, 1e-3, &rng);
    double ds = (std::uniform_int_distribution<int>(0, 1)(rng) ? 1 : -1) * LogUniform(1e-3, 60, &rng);
    // Every other draw puts the interval around the stationary point (26)/(30) when there is one.
    if (K != 0 && draw % 2 == 0) {
      const double c = -lambda * mu * D;
      const double x = ds >= 0 ? (K + std::sqrt(K * K + c)) / mu : (-K + std::sqrt(K * K + c)) / lambda;
      const double s_m = (x + D) / K;
      if ((ds >= 0) == (s_m >= 0)) ds = s_m * std::uniform_real_distribution<double>(1.0, 3.0)(rng);
    }
    if (!SatisfiesNecessaryCondition(ds, K, D) || !std::isfinite(ds)) continue;
    const HMaximum closed = MaxH(K, D, ds, Model(lambda, mu));
    int& hit = hits[static_cast<int>(closed.branch)];
    if (hit >= kPerBranch) continue;
    ++hit;
    ++checks;
    if (closed.branch == HMaxBranch::kEq27Ends || closed.branch == HMaxBranch::kEq29Ends) {
      ++(K > 0 ? ends_with_positive_K : ends_with_negative_K);
    }
    const double numeric = NumericMaxH(K, D, ds, lambda, mu);
    ASSERT_NEAR(closed.value, numeric, 1e-6 * numeric)
        << HMaxBranchName(closed.branch) << " K " << K << " D " << D << " ds " << ds << " lambda " << lambda
        << " mu " << mu;
  }
  std::string report;
  for (int b = 0; b < kNumHMaxBranches; ++b) {
    EXPECT_GE(hits[b], kPerBranch) << HMaxBranchName(static_cast<HMaxBranch>(b));
    report += std::string(HMaxBranchName(static_cast<HMaxBranch>(b))) + ": " + std::to_string(hits[b]) + "; ";
  }
  EXPECT_GT(ends_with_positive_K, 0);
  EXPECT_GT(ends_with_negative_K, 0);
  RecordProperty("branch_hits", report);
  std::printf("closed form vs numeric, %d checks; branch hits: %s(27)/(29) ends K>0 %d, K<0 %d\n", checks,
              report.c_str(), ends_with_positive_K, ends_with_negative_K);
}

TEST(EndpointSupportTest, HIsNonIncreasingInAbsDs) {
  std::mt19937 rng(3);
  int sequences = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double lambda = LogUniform(0.02, 5, &rng), mu = LogUniform(0.02, 5, &rng);
    const double D = -LogUniform(0.05, 20, &rng);
    const double K = std::uniform_int_distribution<int>(0, 4)(rng) == 0 ? 0.0 : std::uniform_real_distribution<double>(-2, 2)(rng);
    const EndpointModel model = Model(lambda, mu);
    for (const double sign : {1.0, -1.0}) {
      double previous = MaxH(K, D, 0, model).value;
      EXPECT_NEAR(previous, -1 / D, 1e-12 / -D);  // ds = 0: h(0) = g(0) = -1/D
      for (double magnitude = 0.05; magnitude < 100; magnitude *= 1.2) {
        const double ds = sign * magnitude;
        if (!SatisfiesNecessaryCondition(ds, K, D)) break;  // past the vanishing point: H = 0
        const double value = MaxH(K, D, ds, model).value;
        ASSERT_LE(value, previous * (1 + 1e-12)) << "K " << K << " D " << D << " ds " << ds;
        previous = value;
      }
      ++sequences;
    }
  }
  EXPECT_EQ(sequences, 4000);
}

TEST(EndpointSupportTest, MirrorSymmetricRigGivesHEqualToHPrime) {
  // Two cameras verged by 5 degrees towards each other from x = -0.2 and x = +0.2 m: the mirror
  // x -> -x of the world swaps them, and in the images it is M: u -> 640 - u. So image 2 of a
  // pair (s1, s2) mirrored, (M s2, M s1), is the same pair seen with the images swapped, and H of
  // the first must equal H' of the second (H is unchanged by moving both images rigidly).
  testing::TwoViews views;
  views.K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  views.world_T_camera1 = Pose3(Eigen::AngleAxisd(5 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                                Eigen::Vector3d(-0.2, 0, 0));
  views.world_T_camera2 = Pose3(Eigen::AngleAxisd(-5 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                                Eigen::Vector3d(0.2, 0, 0));
  const Eigen::Matrix3d F = views.F();
  auto mirror = [](const OrientedSegment& s) {
    return OrientedSegment::FromPoints({640 - s.origin.x(), s.origin.y()}, {640 - s.end.x(), s.end.y()});
  };
  const EndpointModel model = Model(1.0, 0.2);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> along(-4, 2);
  int informative = 0, pairs = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const testing::Junction3d junction3d = testing::RandomJunction3d(views, 3, &rng);
    for (const Eigen::Vector3d& end3d : junction3d.ends) {
      // Images of one 3D segment with end-points moved independently along them.
      OrientedSegment s1 = OrientedSegment::FromPoints(views.Project(0, junction3d.location), views.Project(0, end3d));
      OrientedSegment s2 = OrientedSegment::FromPoints(views.Project(1, junction3d.location), views.Project(1, end3d));
      s1 = OrientedSegment::FromPoints(s1.origin, s1.end + along(rng) * s1.direction);
      s2 = OrientedSegment::FromPoints(s2.origin, s2.end + along(rng) * s2.direction);
      const std::optional<double> h = H(F, s1, s2, model, 1.0, 10.0);
      const std::optional<double> h_prime_mirrored = HPrime(F, mirror(s2), mirror(s1), model, 1.0, 10.0);
      ASSERT_EQ(h.has_value(), h_prime_mirrored.has_value());
      ++pairs;
      if (!h) continue;
      EXPECT_NEAR(*h, *h_prime_mirrored, 1e-9 * *h);
      // And the other way round.
      EXPECT_NEAR(*HPrime(F, s1, s2, model, 1.0, 10.0), *H(F, mirror(s2), mirror(s1), model, 1.0, 10.0),
                  1e-9 * *h);
      const SegmentTransfer transfer = TransferSegment(s1, MakeEndpointEpipolar(F, s1), s2, 1.0, 10.0);
      if (transfer.kind == SegmentTransfer::Case::kGeneral && std::abs(transfer.ds) > 1 &&
          std::abs(transfer.D + 1) > 0.01) {
        ++informative;
      }
    }
  }
  EXPECT_EQ(pairs, 900);
  EXPECT_GT(informative, 300);  // the end-points off each other's epipolar lines, D != -1
}

}  // namespace
}  // namespace sfm

// The orthonormal line parameterisation: Ceres's manifold invariants (Plus(x, 0) = x,
// Minus(Plus(x, d), x) = d, Plus(x, Minus(y, x)) = y, analytic Jacobians against Ridders' numeric
// ones, Minus' Jacobian times Plus' = I) and the conversions to and from point + direction.
#include "backend/bundle_adjustment/line_manifold.h"

#include <ceres/manifold_test_utils.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

namespace sfm {
namespace {

// Relative tolerance of the invariant checks (Ceres's own manifold tests use 1e-9 too for their
// quaternion manifolds; the numeric Jacobians are Ridders' extrapolations).
constexpr double kTolerance = 1e-9;

class RandomLines {
 public:
  double Uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine_);
  }
  Eigen::Vector3d Vector(double low, double high) {
    return Eigen::Vector3d(Uniform(low, high), Uniform(low, high), Uniform(low, high));
  }
  OrthonormalLine Line(double extent) {
    return OrthonormalLineFromPointDirection(Vector(-extent, extent), Vector(-1, 1));
  }
  Eigen::VectorXd Ambient(const OrthonormalLine& line) {
    return Eigen::Map<const Eigen::VectorXd>(line.data(), 6);
  }

 private:
  std::mt19937 engine_{2005};
};

TEST(OrthonormalLineManifoldTest, InvariantsHold) {
  // The macro names ceres's matchers and ceres::Vector unqualified.
  using namespace ceres;  // NOLINT(build/namespaces)
  OrthonormalLineManifold manifold;
  RandomLines random;
  for (int trial = 0; trial < 20; ++trial) {
    // Lines from near the origin to 50 m away; tangent steps up to 1 rad.
    const double extent = trial < 10 ? 5.0 : 50.0;
    const Eigen::VectorXd x = random.Ambient(random.Line(extent));
    const Eigen::VectorXd y = random.Ambient(random.Line(extent));
    Eigen::VectorXd delta(4);
    delta << random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1), random.Uniform(-1, 1);
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, kTolerance);
  }
}

TEST(OrthonormalLineManifoldTest, InvariantsHoldForALineThroughTheOrigin) {
  using namespace ceres;  // NOLINT(build/namespaces)
  OrthonormalLineManifold manifold;
  const OrthonormalLine through_origin = OrthonormalLineFromPointDirection({0, 0, 0}, {0.3, -0.2, 0.9});
  EXPECT_NEAR(through_origin[4], 0, 1e-15);  // w1 = distance / norm = 0
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(through_origin.data(), 6);
  const OrthonormalLine other = OrthonormalLineFromPointDirection({1, 2, 3}, {1, 0, 0});
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(other.data(), 6);
  Eigen::VectorXd delta(4);
  delta << 0.1, -0.2, 0.3, 0.4;
  EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, kTolerance);
}

TEST(OrthonormalLineTest, PointDirectionRoundTrip) {
  RandomLines random;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d point = random.Vector(-10, 10);
    const Eigen::Vector3d direction = random.Vector(-1, 1);
    const OrthonormalLine line = OrthonormalLineFromPointDirection(point, direction);
    Eigen::Vector3d point_back, direction_back;
    OrthonormalLineToPointDirection(line, &point_back, &direction_back);
    const Eigen::Vector3d d = direction.normalized();
    EXPECT_NEAR((direction_back - d).norm(), 0, 1e-12);
    // The point returned is the one closest to the origin: `point` minus its component along d.
    const Eigen::Vector3d closest = point - d * d.dot(point);
    EXPECT_NEAR((point_back - closest).norm(), 0, 1e-12);
    EXPECT_NEAR(point_back.dot(direction_back), 0, 1e-12);
    // Plücker coordinates proportional to (p x d, d).
    Eigen::Vector3d moment, plucker_direction;
    PluckerFromOrthonormal(line.data(), &moment, &plucker_direction);
    const double scale = plucker_direction.norm();
    EXPECT_NEAR((moment / scale - point.cross(d)).norm(), 0, 1e-12);
    EXPECT_NEAR((plucker_direction / scale - d).norm(), 0, 1e-12);
  }
}

// The update of the W part changes only the distance from the origin: with (w1, w2) =
// (cos beta, sin beta), distance = w1 / w2 = cot(beta), and phi adds to beta.
TEST(OrthonormalLineTest, PhiChangesOnlyTheDistanceFromTheOrigin) {
  OrthonormalLineManifold manifold;
  const OrthonormalLine line = OrthonormalLineFromPointDirection({0, 2, 0}, {1, 0, 0});
  const double delta[4] = {0, 0, 0, 0.1};
  OrthonormalLine moved;
  ASSERT_TRUE(manifold.Plus(line.data(), delta, moved.data()));
  Eigen::Vector3d point, direction;
  OrthonormalLineToPointDirection(moved, &point, &direction);
  EXPECT_NEAR((direction - Eigen::Vector3d::UnitX()).norm(), 0, 1e-12);
  EXPECT_NEAR(point.norm(), 1 / std::tan(std::atan(1 / 2.0) + 0.1), 1e-12);
  EXPECT_NEAR((point.normalized() - Eigen::Vector3d::UnitY()).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace sfm

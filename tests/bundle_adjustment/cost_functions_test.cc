// Every residual twice: values on hand-built numbers, then its derivatives against numeric ones
// with ceres::GradientChecker at random points (through the manifolds the solver uses).
#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "backend/bundle_adjustment/floor_prior_cost.h"
#include "backend/bundle_adjustment/line_manifold.h"
#include "backend/bundle_adjustment/line_reprojection_cost.h"
#include "backend/bundle_adjustment/odometry_prior_cost.h"
#include "backend/bundle_adjustment/point_reprojection_cost.h"
#include "backend/bundle_adjustment/pose_parameters.h"
#include "tests/bundle_adjustment/synthetic_room.h"

namespace sfm {
namespace {

// Relative precision asked of GradientChecker: the automatic derivatives against its Ridders
// extrapolation, started at a relative step of 1e-4 as in Ceres's manifold_test_utils.h (its default
// 1e-2 is too coarse for the quaternion blocks: errors up to 4e-2). Observed worst: about 1e-10.
constexpr double kGradientTolerance = 1e-7;
constexpr int kRandomTrials = 20;

ceres::NumericDiffOptions RiddersOptions() {
  ceres::NumericDiffOptions options;
  options.ridders_relative_initial_step_size = 1e-4;
  return options;
}

// The residuals of `cost` (N of them) at `parameters`.
template <int N = 2>
Eigen::Matrix<double, N, 1> Residuals(const ceres::CostFunction& cost, std::vector<const double*> parameters) {
  Eigen::Matrix<double, N, 1> r;
  EXPECT_TRUE(cost.Evaluate(parameters.data(), r.data(), nullptr));
  return r;
}

class Random {
 public:
  double Uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine_);
  }
  Eigen::Vector3d Vector(double low, double high) {
    return Eigen::Vector3d(Uniform(low, high), Uniform(low, high), Uniform(low, high));
  }
  Eigen::Quaterniond Rotation() {
    return Eigen::Quaterniond(Eigen::AngleAxisd(Uniform(0, M_PI), Vector(-1, 1).normalized()));
  }
  Pose3 Pose() { return Pose3(Rotation(), Vector(-5, 5)); }

 private:
  std::mt19937 engine_{12345};
};

// The camera of the synthetic room on an identity base pose, a hand-computable case.
CameraModel SimpleCamera() { return CameraModel(Pose3::Identity(), 500, 400, 320, 240); }

CameraModel RigCamera() {
  const Calibration calibration = testing::RobotCalibration();
  const Camera& camera = calibration.camera;
  return CameraModel(calibration.base_T_camera, camera.fx, camera.fy, camera.cx, camera.cy);
}

TEST(PointReprojectionCostTest, HandBuiltValues) {
  const PoseParameters pose = PoseParameters::FromPose(Pose3::Identity());
  const double point[3] = {1, 2, 10};
  // u = 500 * 1/10 + 320 = 370, v = 400 * 2/10 + 240 = 320.
  std::unique_ptr<ceres::CostFunction> exact(PointReprojectionCost::Create(SimpleCamera(), {370, 320}));
  EXPECT_NEAR(Residuals(*exact, {pose.rotation.data(), pose.translation.data(), point}).norm(), 0, 1e-12);
  std::unique_ptr<ceres::CostFunction> offset(PointReprojectionCost::Create(SimpleCamera(), {371, 320}));
  const Eigen::Vector2d r = Residuals(*offset, {pose.rotation.data(), pose.translation.data(), point});
  EXPECT_NEAR(r.x(), -1, 1e-12);  // projection - observed
  EXPECT_NEAR(r.y(), 0, 1e-12);
}

TEST(PointReprojectionCostTest, WhitenedBySqrtInformation) {
  const PoseParameters pose = PoseParameters::FromPose(Pose3::Identity());
  const double point[3] = {1, 2, 10};  // projects to (370, 320)
  Eigen::Matrix2d sqrt_information;
  sqrt_information << 2, 0.5, 0.5, 1;
  std::unique_ptr<ceres::CostFunction> cost(
      PointReprojectionCost::Create(SimpleCamera(), {371, 318}, sqrt_information));
  // Pixel error (-1, 2): whitened (2 * -1 + 0.5 * 2, 0.5 * -1 + 1 * 2) = (-1, 1.5).
  const Eigen::Vector2d r = Residuals(*cost, {pose.rotation.data(), pose.translation.data(), point});
  EXPECT_NEAR(r.x(), -1, 1e-12);
  EXPECT_NEAR(r.y(), 1.5, 1e-12);
}

TEST(PointReprojectionCostTest, RigAndPoseZeroWhenSeenExactlyOnePixelOff) {
  const CameraModel camera = RigCamera();
  const Pose3 world_T_base(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())),
                           Eigen::Vector3d(2, -1, 0));
  const Pose3 world_T_camera = world_T_base * testing::RobotCalibration().base_T_camera;
  const Eigen::Vector3d point_camera(0.4, -0.3, 3.5);
  const Eigen::Vector3d point_world = world_T_camera * point_camera;
  const Eigen::Vector2d pixel(camera.fx * 0.4 / 3.5 + camera.cx, camera.fy * -0.3 / 3.5 + camera.cy);
  const PoseParameters pose = PoseParameters::FromPose(world_T_base);
  const std::vector<const double*> parameters = {pose.rotation.data(), pose.translation.data(),
                                                 point_world.data()};
  std::unique_ptr<ceres::CostFunction> exact(PointReprojectionCost::Create(camera, pixel));
  EXPECT_NEAR(Residuals(*exact, parameters).norm(), 0, 1e-9);
  const Eigen::Vector2d offset_px = Eigen::Vector2d(0.6, -0.8);  // 1 px
  std::unique_ptr<ceres::CostFunction> offset(PointReprojectionCost::Create(camera, pixel + offset_px));
  EXPECT_NEAR(Residuals(*offset, parameters).norm(), 1, 1e-9);
}

TEST(PointReprojectionCostTest, BehindTheCameraIsRejected) {
  const PoseParameters pose = PoseParameters::FromPose(Pose3::Identity());
  const double point[3] = {1, 2, -10};
  std::unique_ptr<ceres::CostFunction> cost(PointReprojectionCost::Create(SimpleCamera(), {370, 320}));
  Eigen::Vector2d r;
  const double* parameters[] = {pose.rotation.data(), pose.translation.data(), point};
  EXPECT_FALSE(cost->Evaluate(parameters, r.data(), nullptr));
}

TEST(PointReprojectionCostTest, GradientCheck) {
  Random random;
  const CameraModel camera = RigCamera();
  const Pose3 base_T_camera = testing::RobotCalibration().base_T_camera;
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds = {&quaternion, nullptr, nullptr};
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    const Pose3 world_T_base = random.Pose();
    const Eigen::Vector3d point_camera(random.Uniform(-2, 2), random.Uniform(-1.5, 1.5),
                                       random.Uniform(1, 8));
    const Eigen::Vector3d point = (world_T_base * base_T_camera) * point_camera;
    const Eigen::Vector2d observed(random.Uniform(0, 640), random.Uniform(0, 480));
    // A junction location's whitening (symmetric, positive definite), on every other trial.
    Eigen::Matrix2d sqrt_information = Eigen::Matrix2d::Identity();
    if (trial % 2 == 1) {
      const double off = random.Uniform(-0.5, 0.5);
      sqrt_information << random.Uniform(0.5, 2), off, off, random.Uniform(0.5, 2);
    }
    std::unique_ptr<ceres::CostFunction> cost(
        PointReprojectionCost::Create(camera, observed, sqrt_information));
    const PoseParameters pose = PoseParameters::FromPose(world_T_base);
    const double* parameters[] = {pose.rotation.data(), pose.translation.data(), point.data()};
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

TEST(LineReprojectionCostTest, HandBuiltValues) {
  const PoseParameters pose = PoseParameters::FromPose(Pose3::Identity());
  // The line x = 1, z = 5 (direction y) projects to the image column u = 500 * 1/5 + 320 = 420.
  const OrthonormalLine line = OrthonormalLineFromPointDirection({1, 0, 5}, {0, 1, 0});
  const std::vector<const double*> parameters = {pose.rotation.data(), pose.translation.data(), line.data()};
  std::unique_ptr<ceres::CostFunction> exact(
      LineReprojectionCost::Create(SimpleCamera(), {420, 100}, {420, 300}));
  EXPECT_NEAR(Residuals(*exact, parameters).norm(), 0, 1e-9);
  std::unique_ptr<ceres::CostFunction> offset(
      LineReprojectionCost::Create(SimpleCamera(), {421, 100}, {419, 300}));
  const Eigen::Vector2d r = Residuals(*offset, parameters);
  EXPECT_NEAR(std::abs(r.x()), 1, 1e-9);
  EXPECT_NEAR(std::abs(r.y()), 1, 1e-9);
  EXPECT_LT(r.x() * r.y(), 0);  // on either side of the line
  // Moving the end-points along the line changes nothing.
  std::unique_ptr<ceres::CostFunction> along(
      LineReprojectionCost::Create(SimpleCamera(), {420, -50}, {420, 900}));
  EXPECT_NEAR(Residuals(*along, parameters).norm(), 0, 1e-9);
}

TEST(LineReprojectionCostTest, RigAndPoseZeroWhenSeenExactlyOnePixelOff) {
  const CameraModel camera = RigCamera();
  const Pose3 world_T_base(Eigen::Quaterniond(Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitZ())),
                           Eigen::Vector3d(-3, 4, 0));
  const Pose3 world_T_camera = world_T_base * testing::RobotCalibration().base_T_camera;
  const Eigen::Vector3d a_camera(-0.8, 0.5, 4), b_camera(1.1, -0.4, 6);
  auto project = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(camera.fx * p.x() / p.z() + camera.cx, camera.fy * p.y() / p.z() + camera.cy);
  };
  const Eigen::Vector2d a = project(a_camera), b = project(b_camera);
  const Eigen::Vector2d normal = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
  const OrthonormalLine line = OrthonormalLineFromPointDirection(
      world_T_camera * a_camera, world_T_camera * b_camera - world_T_camera * a_camera);
  const PoseParameters pose = PoseParameters::FromPose(world_T_base);
  const std::vector<const double*> parameters = {pose.rotation.data(), pose.translation.data(), line.data()};
  std::unique_ptr<ceres::CostFunction> exact(LineReprojectionCost::Create(camera, a, b));
  EXPECT_NEAR(Residuals(*exact, parameters).norm(), 0, 1e-9);
  std::unique_ptr<ceres::CostFunction> offset(LineReprojectionCost::Create(camera, a + normal, b + normal));
  const Eigen::Vector2d r = Residuals(*offset, parameters);
  EXPECT_NEAR(std::abs(r.x()), 1, 1e-9);
  EXPECT_NEAR(r.y(), r.x(), 1e-9);  // same side, same distance
}

TEST(LineReprojectionCostTest, LineThroughTheCameraCentreIsRejected) {
  const PoseParameters pose = PoseParameters::FromPose(Pose3::Identity());
  const OrthonormalLine line = OrthonormalLineFromPointDirection({0, 0, 0}, {0, 0, 1});
  std::unique_ptr<ceres::CostFunction> cost(
      LineReprojectionCost::Create(SimpleCamera(), {320, 240}, {330, 250}));
  Eigen::Vector2d r;
  const double* parameters[] = {pose.rotation.data(), pose.translation.data(), line.data()};
  EXPECT_FALSE(cost->Evaluate(parameters, r.data(), nullptr));
}

// GradientChecker on random configurations: poses, a line through two random points in front of
// the camera, two random observed end-points; `create` makes the cost function under test.
template <typename Create>
void ExpectLineCostPassesGradientCheck(Create create) {
  Random random;
  const CameraModel camera = RigCamera();
  const Pose3 base_T_camera = testing::RobotCalibration().base_T_camera;
  ceres::EigenQuaternionManifold quaternion;
  OrthonormalLineManifold line_manifold;
  const std::vector<const ceres::Manifold*> manifolds = {&quaternion, nullptr, &line_manifold};
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    const Pose3 world_T_base = random.Pose();
    const Pose3 world_T_camera = world_T_base * base_T_camera;
    const Eigen::Vector3d a(random.Uniform(-2, 2), random.Uniform(-1.5, 1.5), random.Uniform(1, 8));
    const Eigen::Vector3d b(random.Uniform(-2, 2), random.Uniform(-1.5, 1.5), random.Uniform(1, 8));
    const OrthonormalLine line =
        OrthonormalLineFromPointDirection(world_T_camera * a, world_T_camera * b - world_T_camera * a);
    const Eigen::Vector2d p0(random.Uniform(0, 640), random.Uniform(0, 480));
    const Eigen::Vector2d p1(random.Uniform(0, 640), random.Uniform(0, 480));
    std::unique_ptr<ceres::CostFunction> cost(create(camera, p0, p1));
    const PoseParameters pose = PoseParameters::FromPose(world_T_base);
    const double* parameters[] = {pose.rotation.data(), pose.translation.data(), line.data()};
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

// Create's cost function: the analytic Jacobians (LineReprojectionCostFunction).
TEST(LineReprojectionCostTest, GradientCheck) {
  ExpectLineCostPassesGradientCheck(
      [](const CameraModel& c, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1) {
        return LineReprojectionCost::Create(c, p0, p1);
      });
}

// The analytic Jacobians (LineReprojectionCostFunction, what Create returns) against the automatic
// ones of the functor, in the ambient coordinates of every block (so also in the directions off
// the manifolds), on random configurations as above and on the rig with non-unit line scales.
// Tolerance: 1e-9 of the Jacobian's largest entry; they are the same formulas, observed worst
// about 1e-15.
TEST(LineReprojectionCostTest, AnalyticJacobiansMatchTheAutomaticOnes) {
  Random random;
  const CameraModel camera = RigCamera();
  const Pose3 base_T_camera = testing::RobotCalibration().base_T_camera;
  double worst = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Pose3 world_T_base = random.Pose();
    const Pose3 world_T_camera = world_T_base * base_T_camera;
    const Eigen::Vector3d a(random.Uniform(-2, 2), random.Uniform(-1.5, 1.5), random.Uniform(1, 8));
    const Eigen::Vector3d b(random.Uniform(-2, 2), random.Uniform(-1.5, 1.5), random.Uniform(1, 8));
    OrthonormalLine line =
        OrthonormalLineFromPointDirection(world_T_camera * a, world_T_camera * b - world_T_camera * a);
    if (trial % 2 == 1) {  // off the manifold: any scale of (w1, w2), a quaternion of norm != 1
      for (double& value : line) value *= random.Uniform(0.8, 1.2);
    }
    const Eigen::Vector2d p0(random.Uniform(0, 640), random.Uniform(0, 480));
    const Eigen::Vector2d p1(random.Uniform(0, 640), random.Uniform(0, 480));
    std::unique_ptr<ceres::CostFunction> analytic(LineReprojectionCost::Create(camera, p0, p1));
    std::unique_ptr<ceres::CostFunction> automatic(LineReprojectionCost::CreateAutoDiff(camera, p0, p1));
    const PoseParameters pose = PoseParameters::FromPose(world_T_base);
    const double* parameters[] = {pose.rotation.data(), pose.translation.data(), line.data()};
    Eigen::Vector2d r_analytic, r_automatic;
    Eigen::Matrix<double, 2, 4, Eigen::RowMajor> Jq_analytic, Jq_automatic;
    Eigen::Matrix<double, 2, 3, Eigen::RowMajor> Jt_analytic, Jt_automatic;
    Eigen::Matrix<double, 2, 6, Eigen::RowMajor> Jl_analytic, Jl_automatic;
    double* J_analytic[] = {Jq_analytic.data(), Jt_analytic.data(), Jl_analytic.data()};
    double* J_automatic[] = {Jq_automatic.data(), Jt_automatic.data(), Jl_automatic.data()};
    ASSERT_TRUE(analytic->Evaluate(parameters, r_analytic.data(), J_analytic));
    ASSERT_TRUE(automatic->Evaluate(parameters, r_automatic.data(), J_automatic));
    EXPECT_LT((r_analytic - r_automatic).norm(), 1e-12 * (1 + r_automatic.norm()));
    const double scale = std::max({Jq_automatic.cwiseAbs().maxCoeff(), Jt_automatic.cwiseAbs().maxCoeff(),
                                   Jl_automatic.cwiseAbs().maxCoeff()});
    const double error = std::max({(Jq_analytic - Jq_automatic).cwiseAbs().maxCoeff(),
                                   (Jt_analytic - Jt_automatic).cwiseAbs().maxCoeff(),
                                   (Jl_analytic - Jl_automatic).cwiseAbs().maxCoeff()}) /
                         scale;
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-9) << "trial " << trial;
    // The line's Jacobian alone (the pose's not asked for, as in the inner iterations, which skip
    // the rotation's derivatives): the same residuals and entries, bit for bit.
    Eigen::Vector2d r_line_only;
    Eigen::Matrix<double, 2, 6, Eigen::RowMajor> Jl_line_only;
    double* J_line_only[] = {nullptr, nullptr, Jl_line_only.data()};
    ASSERT_TRUE(analytic->Evaluate(parameters, r_line_only.data(), J_line_only));
    EXPECT_EQ(r_line_only, r_analytic) << "trial " << trial;
    EXPECT_EQ(Jl_line_only, Jl_analytic) << "trial " << trial;
  }
  std::printf("[ figures  ] analytic against automatic line Jacobians: worst relative difference %.2e\n", worst);
}

// The automatic reference itself through GradientChecker, as the analytic one above.
TEST(LineReprojectionCostTest, GradientCheckOfTheAutomaticReference) {
  ExpectLineCostPassesGradientCheck(
      [](const CameraModel& c, const Eigen::Vector2d& p0, const Eigen::Vector2d& p1) {
        return LineReprojectionCost::CreateAutoDiff(c, p0, p1);
      });
}

// The odometry prior's six parameter blocks: the two poses, lambda and b.
struct OdometryBlocks {
  OdometryBlocks(const Pose3& est_i, const Pose3& est_j, double lambda = 1,
                 const Eigen::Vector3d& b = Eigen::Vector3d::Zero())
      : i(PoseParameters::FromPose(est_i)), j(PoseParameters::FromPose(est_j)), scale(lambda), bias(b) {}
  PoseParameters i, j;
  double scale;
  Eigen::Vector3d bias;
  std::array<const double*, 6> pointers() const {
    return {i.rotation.data(), i.translation.data(), j.rotation.data(), j.translation.data(), &scale,
            bias.data()};
  }
};

// Manifolds of the six blocks: the quaternions', the rest Euclidean.
std::vector<const ceres::Manifold*> OdometryManifolds(const ceres::Manifold* quaternion) {
  return {quaternion, nullptr, quaternion, nullptr, nullptr, nullptr};
}

TEST(OdometryPriorCostTest, HandBuiltValues) {
  const Pose3 odom_i(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d(1, 2, 0));
  const Pose3 motion(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d(0.2, 0, 0));
  const double rotation_sigma = 0.02, translation_sigma = 0.01;
  std::unique_ptr<ceres::CostFunction> cost(
      OdometryPriorCost::Create(motion, rotation_sigma, translation_sigma, translation_sigma));
  auto residuals = [&](const Pose3& est_i, const Pose3& est_j) {
    const OdometryBlocks blocks(est_i, est_j);
    Eigen::Matrix<double, 6, 1> r;
    EXPECT_TRUE(cost->Evaluate(blocks.pointers().data(), r.data(), nullptr));
    return r;
  };
  // Moving exactly as the odometry says, from anywhere: zero.
  EXPECT_NEAR(residuals(odom_i, odom_i * motion).norm(), 0, 1e-12);
  const Pose3 elsewhere =
      Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 1, 0).normalized())),
            Eigen::Vector3d(-4, 1, 3));
  EXPECT_NEAR(residuals(elsewhere, elsewhere * motion).norm(), 0, 1e-12);
  // One sigma too far along the motion: translation residual (1, 0, 0) in base_j.
  const Pose3 too_far(Eigen::Quaterniond::Identity(), Eigen::Vector3d(translation_sigma, 0, 0));
  Eigen::Matrix<double, 6, 1> r = residuals(odom_i, odom_i * too_far * motion);
  EXPECT_NEAR(r.head<3>().norm(), 0, 1e-12);
  EXPECT_NEAR(r.tail<3>().norm(), 1, 1e-9);
  // One sigma of extra yaw at the end: rotation residual (0, 0, 1).
  const Pose3 turned(Eigen::Quaterniond(Eigen::AngleAxisd(rotation_sigma, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d::Zero());
  r = residuals(odom_i, odom_i * motion * turned);
  EXPECT_NEAR(r(2), 1, 1e-9);
  EXPECT_NEAR(r.head<2>().norm() + r.tail<3>().norm(), 0, 1e-9);
}

// An odometry measurement near the estimated motion est_i^-1 est_j (rotation off by up to 0.5 rad,
// translation by up to 0.3 per axis), so that the rotation error stays below pi.
Pose3 MeasurementNear(Random& random, const Pose3& est_i, const Pose3& est_j) {
  const Pose3 perturbation(
      Eigen::Quaterniond(Eigen::AngleAxisd(random.Uniform(0, 0.5), random.Vector(-1, 1).normalized())),
      random.Vector(-0.3, 0.3));
  return est_i.Inverse() * est_j * perturbation;
}

// Every block, lambda and b included, at random values: lambda in 0.9-1.1, b from none (the first
// trial: the angle-axis conversion's small-angle branch, where the solver starts) to 0.1 rad.
TEST(OdometryPriorCostTest, GradientCheck) {
  Random random;
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds = OdometryManifolds(&quaternion);
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    const Pose3 est_i = random.Pose(), est_j = random.Pose();
    const Pose3 measured = MeasurementNear(random, est_i, est_j);
    std::unique_ptr<ceres::CostFunction> cost(
        OdometryPriorCost::Create(measured, random.Uniform(0.001, 0.1), random.Uniform(0.001, 0.1),
                                  random.Uniform(0.0001, 0.1)));
    const double scale = random.Uniform(0.9, 1.1);
    const Eigen::Vector3d bias = trial == 0 ? Eigen::Vector3d::Zero() : random.Vector(-0.1, 0.1);
    const OdometryBlocks blocks(est_i, est_j, scale, bias);
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(blocks.pointers().data(), kGradientTolerance, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

// At zero error the angle-axis conversion takes its small-angle branch; its derivatives must still
// be exact there (the solver ends near it).
TEST(OdometryPriorCostTest, GradientCheckAtZeroError) {
  Random random;
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds = OdometryManifolds(&quaternion);
  const Pose3 est_i = random.Pose(), est_j = random.Pose();
  std::unique_ptr<ceres::CostFunction> cost(OdometryPriorCost::Create(est_i.Inverse() * est_j, 0.01, 0.02, 0.001));
  const OdometryBlocks blocks(est_i, est_j);
  ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(blocks.pointers().data(), kGradientTolerance, &results)) << results.error_log;
}

// Along and across the step: a step one along-sigma too long, or one across-sigma to the side (in
// either direction across, horizontal or vertical), gives a whitened translation residual of 1;
// the rotation residuals are untouched. Tolerance 1e-9.
TEST(OdometryPriorCostTest, AlongAndAcrossTheStep) {
  const Pose3 odom_i(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(1, 2, 0));
  // A step of 0.2 m, 30 deg left of base_i's x axis, turning 0.1 rad.
  const Eigen::Vector3d direction(std::cos(0.5236), std::sin(0.5236), 0);
  const Pose3 motion(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())), 0.2 * direction);
  const double along_sigma = 0.004, across_sigma = 0.0005;
  std::unique_ptr<ceres::CostFunction> cost(OdometryPriorCost::Create(motion, 0.002, along_sigma, across_sigma));
  auto translation_residual = [&](const Eigen::Vector3d& offset_in_base_i) {
    const Pose3 est_i = odom_i;
    const Pose3 est_j = odom_i * Pose3(Eigen::Quaterniond::Identity(), offset_in_base_i) * motion;
    const OdometryBlocks blocks(est_i, est_j);
    Eigen::Matrix<double, 6, 1> r;
    EXPECT_TRUE(cost->Evaluate(blocks.pointers().data(), r.data(), nullptr));
    EXPECT_NEAR(r.head<3>().norm(), 0, 1e-12);
    return r.tail<3>().norm();
  };
  EXPECT_NEAR(translation_residual(along_sigma * direction), 1, 1e-9);
  EXPECT_NEAR(translation_residual(-along_sigma * direction), 1, 1e-9);
  const Eigen::Vector3d sideways(-direction.y(), direction.x(), 0);
  EXPECT_NEAR(translation_residual(across_sigma * sideways), 1, 1e-9);
  EXPECT_NEAR(translation_residual(across_sigma * Eigen::Vector3d::UnitZ()), 1, 1e-9);
  // Both at once: the squares add.
  EXPECT_NEAR(translation_residual(along_sigma * direction + across_sigma * sideways), std::sqrt(2.0), 1e-9);
}

// The rule of the sigmas (docs/bundle_adjustment.md, "Odometry prior"): along = translation_sigma
// * d, across = rotation_sigma * d, d the distance floored at odometry_min_distance_m; a step
// shorter than the floor gets the larger of the two in every direction. Exact to 1e-15.
TEST(OdometryPriorCostTest, StepSigmas) {
  OdometryNoise noise;
  noise.translation_sigma = 0.0224;
  noise.rotation_sigma = 0.00224;
  BundleAdjustmentOptions options;  // odometry_min_distance_m 0.05
  OdometryStepSigmas sigmas = OdometryStepSigmasFor(0.2, noise, options);
  EXPECT_NEAR(sigmas.along_m, 0.0224 * 0.2, 1e-15);
  EXPECT_NEAR(sigmas.across_m, 0.00224 * 0.2, 1e-15);
  sigmas = OdometryStepSigmasFor(0.01, noise, options);  // below the floor: isotropic
  EXPECT_NEAR(sigmas.along_m, 0.0224 * 0.05, 1e-15);
  EXPECT_NEAR(sigmas.across_m, 0.0224 * 0.05, 1e-15);
  sigmas = OdometryStepSigmasFor(0, noise, options);
  EXPECT_EQ(sigmas.along_m, sigmas.across_m);
  EXPECT_GT(sigmas.along_m, 0);
  // Heading noise larger than the distance noise: across is the looser one.
  noise.translation_sigma = 1e-4;
  sigmas = OdometryStepSigmasFor(0.2, noise, options);
  EXPECT_NEAR(sigmas.along_m, 1e-4 * 0.2, 1e-15);
  EXPECT_NEAR(sigmas.across_m, 0.00224 * 0.2, 1e-15);
}

// lambda scales the measured translation: at lambda = s the residuals are those of the
// measurement with its translation times s and lambda = 1. Tolerance 1e-12 relative.
TEST(OdometryPriorCostTest, ScaleStretchesTheMeasuredStep) {
  Random random;
  for (int trial = 0; trial < 5; ++trial) {
    const Pose3 est_i = random.Pose(), est_j = random.Pose();
    const Pose3 motion(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ())),
                       Eigen::Vector3d(0.3, 0.05, 0));
    Pose3 stretched = motion;
    stretched.translation *= 0.97;
    std::unique_ptr<ceres::CostFunction> cost(OdometryPriorCost::Create(motion, 0.01, 0.02, 0.02));
    std::unique_ptr<ceres::CostFunction> stretched_cost(
        OdometryPriorCost::Create(stretched, 0.01, 0.02, 0.02));
    Eigen::Matrix<double, 6, 1> r_scaled, r_stretched;
    ASSERT_TRUE(
        cost->Evaluate(OdometryBlocks(est_i, est_j, 0.97).pointers().data(), r_scaled.data(), nullptr));
    ASSERT_TRUE(stretched_cost->Evaluate(OdometryBlocks(est_i, est_j).pointers().data(), r_stretched.data(),
                                         nullptr));
    EXPECT_LT((r_scaled - r_stretched).norm(), 1e-12 * (1 + r_stretched.norm()));
  }
}

TEST(FloorPointCostTest, ValuesAndGradientCheck) {
  std::unique_ptr<ceres::CostFunction> cost(FloorPointCost::Create(0.01));
  const std::vector<const ceres::Manifold*> manifolds = {nullptr};
  Random random;
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    const Eigen::Vector3d point = random.Vector(-5, 5);
    const double* parameters[] = {point.data()};
    double r = 0;
    ASSERT_TRUE(cost->Evaluate(parameters, &r, nullptr));
    EXPECT_NEAR(r, point.z() / 0.01, 1e-12);  // metres over sigma
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results)) << results.error_log;
  }
}

TEST(FloorLineCostTest, HandBuiltValues) {
  const double sigma = 0.01;
  auto residuals = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& anchor0,
                       const Eigen::Vector3d& anchor1) {
    std::unique_ptr<ceres::CostFunction> cost(FloorLineCost::Create(anchor0, anchor1, sigma));
    const OrthonormalLine line = OrthonormalLineFromPointDirection(a, b - a);
    return Residuals(*cost, {line.data()});
  };
  // A floor line: zero, wherever the anchors are along or beside it.
  EXPECT_NEAR(residuals({1, 2, 0}, {4, 3, 0}, {0, 0, 0.3}, {9, 1, -2}).norm(), 0, 1e-12);
  // 5 cm above the floor, horizontal: 5 sigma at both anchors.
  Eigen::Vector2d r = residuals({1, 2, 0.05}, {4, 2, 0.05}, {1, 2, 0}, {4, 2, 0});
  EXPECT_NEAR(r(0), 5, 1e-9);
  EXPECT_NEAR(r(1), 5, 1e-9);
  // Rising 10 cm from anchor 0 to anchor 1 (3 m apart): 0 and 10 sigma; the anchors' offsets
  // across the line do not matter.
  r = residuals({1, 2, 0}, {4, 2, 0.1}, {1, 2.5, 0}, {4, 1.0, 0.1});
  EXPECT_NEAR(r(0), 0, 1e-9);
  EXPECT_NEAR(r(1), 10, 1e-9);
}

TEST(FloorLineCostTest, GradientCheck) {
  Random random;
  OrthonormalLineManifold line_manifold;
  const std::vector<const ceres::Manifold*> manifolds = {&line_manifold};
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    const Eigen::Vector3d a = random.Vector(-5, 5), b = random.Vector(-5, 5);
    const OrthonormalLine line = OrthonormalLineFromPointDirection(a, b - a);
    std::unique_ptr<ceres::CostFunction> cost(
        FloorLineCost::Create(a + random.Vector(-0.5, 0.5), b + random.Vector(-0.5, 0.5), random.Uniform(0.005, 0.05)));
    const double* parameters[] = {line.data()};
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

// A base 2 cm above the floor, tilted 0.005 rad about the world x axis: residuals 2 sigma in z, and
// the base's z axis leans towards -y by sin(0.005), so (0, -sin(0.005)) / tilt sigma; a level base on the
// floor, whatever its heading and position in the plane: zero. Tolerance 1e-12.
TEST(BaseOnFloorCostTest, HandBuiltValues) {
  std::unique_ptr<ceres::CostFunction> cost(BaseOnFloorCost::Create(0.01, 0.002));
  const PoseParameters level = PoseParameters::FromPose(
      Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(3, -4, 0)));
  EXPECT_NEAR(Residuals<3>(*cost, {level.rotation.data(), level.translation.data()}).norm(), 0, 1e-12);
  const PoseParameters tilted = PoseParameters::FromPose(
      Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.005, Eigen::Vector3d::UnitX())), Eigen::Vector3d(1, 2, 0.02)));
  const Eigen::Vector3d r = Residuals<3>(*cost, {tilted.rotation.data(), tilted.translation.data()});
  EXPECT_NEAR(r(0), 2, 1e-12);
  EXPECT_NEAR(r(1), 0, 1e-12);
  EXPECT_NEAR(r(2), -std::sin(0.005) / 0.002, 1e-12);
}

TEST(BaseOnFloorCostTest, GradientCheck) {
  Random random;
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds = {&quaternion, nullptr};
  for (int trial = 0; trial < kRandomTrials; ++trial) {
    std::unique_ptr<ceres::CostFunction> cost(
        BaseOnFloorCost::Create(random.Uniform(0.005, 0.05), random.Uniform(0.001, 0.05)));
    const PoseParameters pose = PoseParameters::FromPose(random.Pose());
    const double* parameters[] = {pose.rotation.data(), pose.translation.data()};
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    checker.Probe(parameters, kGradientTolerance, &results);
    // The up vector's x does not depend on a turn about x (nor y on y): structural zeros, which
    // Probe's relative test flags at rounding level (1e-15 against 1e-13). So: each entry of the
    // tangent-space Jacobians within kGradientTolerance of the larger of 1 and its size.
    ASSERT_EQ(results.local_jacobians.size(), 2u);
    for (size_t block = 0; block < 2; ++block) {
      const Eigen::MatrixXd& user = results.local_jacobians[block];
      const Eigen::MatrixXd& numeric = results.local_numeric_jacobians[block];
      for (int r = 0; r < user.rows(); ++r) {
        for (int c = 0; c < user.cols(); ++c) {
          const double size = std::max({1.0, std::abs(user(r, c)), std::abs(numeric(r, c))});
          EXPECT_LE(std::abs(user(r, c) - numeric(r, c)), kGradientTolerance * size)
              << "trial " << trial << " block " << block << " (" << r << ", " << c << ")";
        }
      }
    }
  }
}

// b turns the estimated motion before the comparison: an odometry that turned b more than the
// estimate every step (the generator's R' = Rz(b) R) is matched exactly by that b. Tolerance 1e-9.
TEST(OdometryPriorCostTest, BiasTurnsTheEstimatedMotion) {
  const Pose3 est_i(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                    Eigen::Vector3d(1, 2, 0));
  const Pose3 motion(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d(0.2, 0.01, 0));
  const Pose3 est_j = est_i * motion;
  const Eigen::Vector3d b(0.0004, -0.0002, 0.001);
  const Pose3 measured(Eigen::Quaterniond(Eigen::AngleAxisd(b.norm(), b.normalized())) * motion.rotation,
                       motion.translation);
  const double sigma = 0.002;
  std::unique_ptr<ceres::CostFunction> cost(OdometryPriorCost::Create(measured, sigma, 0.004, 0.0005));
  Eigen::Matrix<double, 6, 1> r;
  ASSERT_TRUE(cost->Evaluate(OdometryBlocks(est_i, est_j, 1, b).pointers().data(), r.data(), nullptr));
  EXPECT_NEAR(r.norm(), 0, 1e-9);
  ASSERT_TRUE(cost->Evaluate(OdometryBlocks(est_i, est_j).pointers().data(), r.data(), nullptr));
  // Without the bias the rotation residual is the bias in sigmas (measured minus estimated: -b,
  // expressed in base_j, which for these small angles is b to 1e-4 relative).
  EXPECT_NEAR((r.head<3>() + motion.rotation.conjugate() * b / sigma).norm(), 0, 1e-6);
}

TEST(OdometryRotationBiasPriorCostTest, ValuesAndGradientCheck) {
  std::unique_ptr<ceres::CostFunction> cost(OdometryRotationBiasPriorCost::Create(0.002));
  const std::vector<const ceres::Manifold*> manifolds = {nullptr};
  const Eigen::Vector3d b(0.001, -0.0005, 0.004);
  const double* parameters[] = {b.data()};
  Eigen::Vector3d r;
  ASSERT_TRUE(cost->Evaluate(parameters, r.data(), nullptr));
  EXPECT_NEAR((r - b / 0.002).norm(), 0, 1e-12);
  ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results)) << results.error_log;
}

TEST(OdometryScalePriorCostTest, ValuesAndGradientCheck) {
  std::unique_ptr<ceres::CostFunction> cost(OdometryScalePriorCost::Create(0.02));
  const std::vector<const ceres::Manifold*> manifolds = {nullptr};
  for (const double scale : {1.0, 0.97, 1.05}) {
    const double* parameters[] = {&scale};
    double r = 0;
    ASSERT_TRUE(cost->Evaluate(parameters, &r, nullptr));
    EXPECT_NEAR(r, (scale - 1) / 0.02, 1e-12);
    ceres::GradientChecker checker(cost.get(), &manifolds, RiddersOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, kGradientTolerance, &results)) << results.error_log;
  }
}

}  // namespace
}  // namespace sfm

#include "sequences/importers/shared_camera_refit.h"

#include <ceres/gradient_checker.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "sequences/importers/shared_camera_refit_costs.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;

// Views of a point cloud by one camera, the motion general enough (rotations about all three
// axes, translation sideways, up and forward) that K is observable, unlike a pure forward motion.
struct Scene {
  Eigen::Matrix3d K;
  double k1 = 0;
  std::vector<Pose3> camera_T_world;
  std::vector<Eigen::Vector3d> points;
  std::vector<RefitObservation> observations;
};

Scene MakeScene(double k1) {
  Scene scene;
  scene.K << 500, 0, 300, 0, 505, 250, 0, 0, 1;
  scene.k1 = k1;
  for (int i = 0; i < 200; ++i) {
    scene.points.emplace_back(-3 + 6 * std::fmod(0.618 * i, 1.0), -2 + 4 * std::fmod(0.382 * i + 0.1, 1.0),
                              6 + 4 * std::fmod(0.7548 * i + 0.3, 1.0));
  }
  for (int v = 0; v < 8; ++v) {
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.06 * v - 0.2, Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(0.05 * std::sin(v), Eigen::Vector3d::UnitX()) *
                                      Eigen::AngleAxisd(0.08 * std::cos(v), Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d centre(0.5 * v - 1.5, 0.3 * std::sin(1.3 * v), 0.4 * v);
    const Pose3 world_T_camera(rotation, centre);
    scene.camera_T_world.push_back(world_T_camera.Inverse());
    for (size_t p = 0; p < scene.points.size(); ++p) {
      const Eigen::Vector2d pixel =
          ProjectWithRadial(scene.K, k1, scene.camera_T_world.back() * scene.points[p]);
      if (pixel.minCoeff() < 0 || pixel.x() > 600 || pixel.y() > 500) continue;
      scene.observations.push_back({v, static_cast<int>(p), pixel});
    }
  }
  return scene;
}

std::vector<Eigen::Vector3d> Centres(const std::vector<Pose3>& camera_T_world) {
  std::vector<Eigen::Vector3d> centres;
  for (const Pose3& pose : camera_T_world) centres.push_back(pose.Inverse().translation);
  return centres;
}

// The start: K off by 4 % in focal length and 20 px in the principal point, every pose turned by
// ~0.01 rad and moved by ~0.05 units, every point moved by ~0.05 units.
struct Start {
  Eigen::Matrix3d K;
  std::vector<Pose3> poses;
  std::vector<Eigen::Vector3d> points;
};
Start Perturbed(const Scene& scene) {
  Start start{scene.K, scene.camera_T_world, scene.points};
  start.K(0, 0) *= 1.04;
  start.K(1, 1) *= 0.97;
  start.K(0, 2) += 20;
  start.K(1, 2) -= 15;
  for (size_t v = 1; v < start.poses.size(); ++v) {
    const double s = std::sin(3.0 * v);
    start.poses[v] =
        Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * s, Eigen::Vector3d(1, s, 0.5).normalized())),
              Eigen::Vector3d(0.05 * s, -0.03, 0.04 * std::cos(2.0 * v))) *
        start.poses[v];
  }
  for (size_t p = 0; p < start.points.size(); ++p) {
    start.points[p] += 0.05 * Eigen::Vector3d(std::sin(1.0 * p), std::cos(1.7 * p), std::sin(2.3 * p));
  }
  return start;
}

// The self-calibrating refit recovers a shared K, the poses and the points from a perturbed start
// when the observations are exact: K to 1e-3 px, centres to 1e-5 units, rotations to 1e-6 rad,
// reprojection to 1e-4 px (the start is tens of pixels off).
TEST(SharedCameraRefitTest, RecoversSharedIntrinsicsPosesAndPoints) {
  const Scene scene = MakeScene(/*k1=*/0);
  const auto [K, poses, points] = Perturbed(scene);
  SharedCameraRefit refit;
  ASSERT_TRUE(RefitSharedCamera(K, poses, points, scene.observations, Centres(scene.camera_T_world),
                                SharedCameraRefitOptions(), &refit)
                  .ok());
  EXPECT_GT(refit.start_median_px, 5.0);
  EXPECT_LT(refit.median_px, 1e-4);
  EXPECT_LT((refit.K - scene.K).cwiseAbs().maxCoeff(), 1e-3) << refit.K;
  EXPECT_EQ(refit.k1, 0);
  ASSERT_EQ(refit.camera_T_world.size(), scene.camera_T_world.size());
  for (size_t v = 0; v < scene.camera_T_world.size(); ++v) {
    EXPECT_LT(refit.centre_offset[v], 1e-5) << "view " << v;
    EXPECT_LT(RotationAngle(refit.camera_T_world[v].rotation, scene.camera_T_world[v].rotation), 1e-6)
        << "view " << v;
  }
  for (size_t p = 0; p < scene.points.size(); p += 17)
    EXPECT_LT((refit.points[p] - scene.points[p]).norm(), 1e-4);
}

// With k1 estimated too, a radial distortion of -0.1 (13 px at the image corner) is recovered to
// 1e-5 and K to 1e-3 px.
TEST(SharedCameraRefitTest, RecoversRadialDistortion) {
  const Scene scene = MakeScene(/*k1=*/-0.1);
  const auto [K, poses, points] = Perturbed(scene);
  SharedCameraRefitOptions options;
  options.radial_k1 = true;
  SharedCameraRefit refit;
  ASSERT_TRUE(
      RefitSharedCamera(K, poses, points, scene.observations, Centres(scene.camera_T_world), options, &refit)
          .ok());
  EXPECT_NEAR(refit.k1, -0.1, 1e-5);
  EXPECT_LT((refit.K - scene.K).cwiseAbs().maxCoeff(), 1e-3) << refit.K;
  EXPECT_LT(refit.median_px, 1e-4);
}

// With K held, K comes back exactly as given, and poses and points still fit: the start's K is the
// true one, so the exact observations are reproduced to 1e-4 px.
TEST(SharedCameraRefitTest, HeldIntrinsicsStayAsGiven) {
  const Scene scene = MakeScene(/*k1=*/0);
  const auto [K, poses, points] = Perturbed(scene);
  SharedCameraRefitOptions options;
  options.refine_focal = false;
  options.refine_principal_point = false;
  SharedCameraRefit refit;
  ASSERT_TRUE(RefitSharedCamera(scene.K, poses, points, scene.observations, Centres(scene.camera_T_world),
                                options, &refit)
                  .ok());
  EXPECT_EQ(refit.K, scene.K);
  EXPECT_LT(refit.median_px, 1e-4);
  // Only the focal length held: the principal point is estimated from the perturbed start.
  options.refine_principal_point = true;
  Eigen::Matrix3d start = scene.K;
  start(0, 2) += 20;
  start(1, 2) -= 15;
  ASSERT_TRUE(RefitSharedCamera(start, poses, points, scene.observations, Centres(scene.camera_T_world),
                                options, &refit)
                  .ok());
  EXPECT_EQ(refit.K(0, 0), scene.K(0, 0));
  EXPECT_EQ(refit.K(1, 1), scene.K(1, 1));
  EXPECT_NEAR(refit.K(0, 2), scene.K(0, 2), 1e-3);
  EXPECT_NEAR(refit.K(1, 2), scene.K(1, 2), 1e-3);
}

// A k1 given and held (a known distortion) stays exactly as given and the distorted observations
// are fitted to 1e-4 px; held at 0 instead, the same views leave pixels of error.
TEST(SharedCameraRefitTest, HeldRadialDistortionStaysAsGiven) {
  const Scene scene = MakeScene(/*k1=*/-0.1);
  const auto [K, poses, points] = Perturbed(scene);
  SharedCameraRefitOptions options;
  options.refine_focal = false;
  options.refine_principal_point = false;
  options.k1 = -0.1;
  SharedCameraRefit refit;
  ASSERT_TRUE(RefitSharedCamera(scene.K, poses, points, scene.observations, Centres(scene.camera_T_world),
                                options, &refit)
                  .ok());
  EXPECT_EQ(refit.k1, -0.1);
  EXPECT_LT(refit.median_px, 1e-4);
  options.k1 = 0;
  ASSERT_TRUE(RefitSharedCamera(scene.K, poses, points, scene.observations, Centres(scene.camera_T_world),
                                options, &refit)
                  .ok());
  EXPECT_EQ(refit.k1, 0);
  EXPECT_GT(refit.median_px, 0.1);
}

// The gauge: the result lies in the reference centres' frame and units. The reference here is the
// truth moved by a similarity (scale 2.5, a rotation, a translation), as a data set's world is any
// frame; the refit centres must land on it (1e-5 of its units), the points with them, and the
// similarity's scale must be reported. Pose 0 of the start is not where the reference puts it, so
// this also checks that the solve's own gauge (pose 0 held) does not leak into the result.
TEST(SharedCameraRefitTest, ResultLiesInTheReferenceFrameAndUnits) {
  const Scene scene = MakeScene(/*k1=*/0);
  const auto [K, poses, points] = Perturbed(scene);
  const double scale = 2.5;
  const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d translation(4, -1, 2);
  auto moved = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return scale * (rotation * x) + translation;
  };
  std::vector<Eigen::Vector3d> reference;
  for (const Eigen::Vector3d& c : Centres(scene.camera_T_world)) reference.push_back(moved(c));
  SharedCameraRefit refit;
  ASSERT_TRUE(
      RefitSharedCamera(K, poses, points, scene.observations, reference, SharedCameraRefitOptions(), &refit)
          .ok());
  // The solve held the start's first-to-last distance; the similarity scales that to the reference's.
  const std::vector<Eigen::Vector3d> start = Centres(poses);
  EXPECT_NEAR(refit.gauge_scale,
              (reference.back() - reference.front()).norm() / (start.back() - start.front()).norm(), 1e-5);
  const std::vector<Eigen::Vector3d> centres = Centres(refit.camera_T_world);
  for (size_t v = 0; v < reference.size(); ++v) {
    EXPECT_LT((centres[v] - reference[v]).norm(), 1e-5 * scale) << "view " << v;
    EXPECT_LT(refit.centre_offset[v], 1e-5 * scale);
  }
  for (size_t p = 0; p < scene.points.size(); p += 17) {
    EXPECT_LT((refit.points[p] - moved(scene.points[p])).norm(), 1e-4 * scale);
  }
  EXPECT_LT(refit.median_px, 1e-4);  // a similarity of the whole solution projects alike
}

TEST(SharedCameraRefitTest, BadInputIsRefused) {
  const Scene scene = MakeScene(/*k1=*/0);
  const std::vector<Eigen::Vector3d> centres = Centres(scene.camera_T_world);
  SharedCameraRefit refit;
  std::vector<RefitObservation> observations = scene.observations;
  observations.push_back({3, 999, Eigen::Vector2d(1, 1)});
  EXPECT_THAT(RefitSharedCamera(scene.K, scene.camera_T_world, scene.points, observations, centres,
                                SharedCameraRefitOptions(), &refit)
                  .message(),
              HasSubstr("observation of point 999 in view 3 is out of range"));
  observations.clear();
  int kept_in_view_2 = 0;
  for (const RefitObservation& o : scene.observations) {
    if (o.view != 2 || ++kept_in_view_2 <= 5) observations.push_back(o);
  }
  EXPECT_THAT(RefitSharedCamera(scene.K, scene.camera_T_world, scene.points, observations, centres,
                                SharedCameraRefitOptions(), &refit)
                  .message(),
              HasSubstr("view 2 has 5 observations; at least 6 are needed"));
  EXPECT_THAT(RefitSharedCamera(scene.K, scene.camera_T_world, scene.points, scene.observations,
                                std::vector<Eigen::Vector3d>(3), SharedCameraRefitOptions(), &refit)
                  .message(),
              HasSubstr("3 reference centres for 8 views"));
}

// The refit's two residuals: values on hand-built numbers, then their automatic derivatives against
// numeric ones (ceres::GradientChecker, Ridders from a relative step of 1e-4 as in the bundle
// adjustment's cost tests) at random points. Tolerance 1e-7 relative; observed about 1e-10.
TEST(SharedCameraRefitCostsTest, HandBuiltValues) {
  // Identity pose; the point (1, 2, 4) -> normalised (0.25, 0.5), r^2 = 0.3125; k1 = -0.1 gives the
  // factor 0.96875, so u = 500 * 0.25 * 0.96875 + 300 = 421.09375, v = 400 * 0.5 * 0.96875 + 200 = 393.75.
  const double intrinsics[4] = {500, 400, 300, 200};
  const double k1[1] = {-0.1};
  const double pose[6] = {0, 0, 0, 0, 0, 0};
  const double point[3] = {1, 2, 4};
  double r[2];
  RefitReprojectionCost({421.09375, 393.75})(intrinsics, k1, pose, point, r);
  EXPECT_NEAR(r[0], 0, 1e-12);
  EXPECT_NEAR(r[1], 0, 1e-12);
  RefitReprojectionCost({420, 395})(intrinsics, k1, pose, point, r);
  EXPECT_NEAR(r[0], 1.09375, 1e-12);
  EXPECT_NEAR(r[1], -1.25, 1e-12);
  // A camera translated by t = (0, 0, -3) has its centre at (0, 0, 3): 5 from (0, 0, -2), so a held
  // distance of 4 gives the weight times (5 / 4 - 1).
  const double moved[6] = {0, 0, 0, 0, 0, -3};
  double g[1];
  RefitCentreDistanceCost(Eigen::Vector3d(0, 0, -2), 4.0)(moved, g);
  EXPECT_NEAR(g[0], kScaleGaugeWeight * 0.25, 1e-12);
  // A rotated camera: centre = -R^T t. R = 90 deg about z, t = (1, 0, 0) -> centre (0, 1, 0).
  const double turned[6] = {0, 0, M_PI / 2, 1, 0, 0};
  RefitCentreDistanceCost(Eigen::Vector3d(0, 0, 0), 1.0)(turned, g);
  EXPECT_NEAR(g[0], 0, 1e-12);
}

TEST(SharedCameraRefitCostsTest, GradientCheck) {
  std::mt19937 engine(7);
  auto uniform = [&engine](double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(engine);
  };
  ceres::NumericDiffOptions ridders;
  ridders.ridders_relative_initial_step_size = 1e-4;
  for (int trial = 0; trial < 20; ++trial) {
    const double intrinsics[4] = {uniform(400, 600), uniform(400, 600), uniform(250, 350), uniform(200, 300)};
    const double k1[1] = {uniform(-0.3, 0.1)};
    const double pose[6] = {uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5),
                            uniform(-1, 1),     uniform(-1, 1),     uniform(-1, 1)};
    // A point in front of the camera: its camera coordinates, taken back to the world.
    const Eigen::Vector3d w(pose[0], pose[1], pose[2]);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    const Eigen::Vector3d in_camera(uniform(-2, 2), uniform(-2, 2), uniform(2, 8));
    const Eigen::Vector3d point = R.transpose() * (in_camera - Eigen::Vector3d(pose[3], pose[4], pose[5]));
    std::unique_ptr<ceres::CostFunction> reprojection(
        new ceres::AutoDiffCostFunction<RefitReprojectionCost, 2, 4, 1, 6, 3>(
            new RefitReprojectionCost({uniform(0, 512), uniform(0, 512)})));
    const double* blocks[] = {intrinsics, k1, pose, point.data()};
    const std::vector<const ceres::Manifold*>* euclidean = nullptr;  // every block plain
    ceres::GradientChecker reprojection_checker(reprojection.get(), euclidean, ridders);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(reprojection_checker.Probe(blocks, 1e-7, &results))
        << "trial " << trial << ": " << results.error_log;

    std::unique_ptr<ceres::CostFunction> distance(
        new ceres::AutoDiffCostFunction<RefitCentreDistanceCost, 1, 6>(new RefitCentreDistanceCost(
            Eigen::Vector3d(uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)), uniform(1, 5))));
    const double* pose_block[] = {pose};
    ceres::GradientChecker distance_checker(distance.get(), euclidean, ridders);
    EXPECT_TRUE(distance_checker.Probe(pose_block, 1e-7, &results))
        << "trial " << trial << ": " << results.error_log;
  }
}

}  // namespace
}  // namespace sfm

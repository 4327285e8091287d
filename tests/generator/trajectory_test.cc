#include "sequences/generator/trajectory.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sequences/generator/camera_rig.h"
#include "sequences/generator/scene_builder.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;

Scene MakeScene(SceneType type, double corridor_length = 16) {
  SceneOptions options;
  options.type = type;
  options.corridor_length = corridor_length;
  Scene scene;
  EXPECT_TRUE(BuildScene(options, 1, &scene).ok());
  return scene;
}

double Yaw(const Pose3& pose) {
  const Eigen::Vector3d x = pose.rotation * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}
double WrappedDifference(double a, double b) { return std::remainder(a - b, 2 * kPi); }

TEST(TrajectoryTest, StraightGoesForwardStepByStep) {
  const Scene scene = MakeScene(SceneType::kCorridor);
  TrajectoryOptions options;
  options.num_frames = 30;
  std::vector<Pose3> poses;
  ASSERT_TRUE(MakeTrajectory(options, scene, &poses).ok());
  ASSERT_EQ(poses.size(), 30u);
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(poses[i].translation.x(), 1.0 + 0.2 * i, 1e-12);
    EXPECT_NEAR(poses[i].translation.y(), scene.lane_y, 1e-12);
    EXPECT_EQ(poses[i].translation.z(), 0);
    EXPECT_NEAR(Yaw(poses[i]), 0, 1e-15);
  }
}

TEST(TrajectoryTest, LoopClosesAndTurnsGently) {
  const Scene scene = MakeScene(SceneType::kRoom);
  TrajectoryOptions options;
  options.type = TrajectoryType::kLoop;
  options.num_frames = 0;  // one lap
  std::vector<Pose3> poses;
  const Status status = MakeTrajectory(options, scene, &poses);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_GT(poses.size(), 40u);
  double total_turn = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const Pose3& a = poses[i];
    const Pose3& b = poses[(i + 1) % poses.size()];  // the lap closes: the last frame leads to the first
    const double step = (b.translation - a.translation).norm();
    const double turn = WrappedDifference(Yaw(b), Yaw(a));
    EXPECT_LE(step, options.step + 1e-9);
    EXPECT_GE(step, 0.05);
    EXPECT_LE(std::abs(turn), options.max_turn_per_frame + 1e-9);
    total_turn += turn;
  }
  EXPECT_NEAR(total_turn, 2 * kPi, 1e-9);
}

TEST(TrajectoryTest, TurnsWeaveAroundTheLane) {
  const Scene scene = MakeScene(SceneType::kCorridor, 20);
  TrajectoryOptions options;
  options.type = TrajectoryType::kTurns;
  options.num_frames = 70;
  std::vector<Pose3> poses;
  const Status status = MakeTrajectory(options, scene, &poses);
  ASSERT_TRUE(status.ok()) << status.message();
  double min_yaw = 0, max_yaw = 0, min_y = 1e9, max_y = -1e9;
  for (size_t i = 0; i < poses.size(); ++i) {
    min_yaw = std::min(min_yaw, Yaw(poses[i]));
    max_yaw = std::max(max_yaw, Yaw(poses[i]));
    min_y = std::min(min_y, poses[i].translation.y());
    max_y = std::max(max_y, poses[i].translation.y());
    if (i > 0) {
      EXPECT_LE(std::abs(WrappedDifference(Yaw(poses[i]), Yaw(poses[i - 1]))), options.max_turn_per_frame + 1e-9);
    }
  }
  EXPECT_NEAR(max_yaw, options.turn_angle, 1e-9);
  EXPECT_NEAR(min_yaw, -options.turn_angle, 1e-9);
  EXPECT_NEAR(0.5 * (min_y + max_y), scene.lane_y, 1e-9);
}

TEST(TrajectoryTest, RefusesPathsThatHitTheScene) {
  const Scene corridor = MakeScene(SceneType::kCorridor);
  std::vector<Pose3> poses;
  TrajectoryOptions loop;
  loop.type = TrajectoryType::kLoop;
  EXPECT_THAT(MakeTrajectory(loop, corridor, &poses).message(), HasSubstr("does not fit"));
  TrajectoryOptions sideways;
  sideways.lane_offset = 0.7;
  EXPECT_THAT(MakeTrajectory(sideways, corridor, &poses).message(), HasSubstr("within robot_radius of a"));
  TrajectoryOptions too_long;
  too_long.num_frames = 200;
  EXPECT_THAT(MakeTrajectory(too_long, corridor, &poses).message(), HasSubstr("wall"));
}

TEST(TrajectoryTest, ExtentMatchesTheStraightPath) {
  TrajectoryOptions options;
  options.num_frames = 41;
  EXPECT_NEAR(TrajectoryExtentX(options), 8.0, 1e-12);
}

TEST(CameraRigTest, CameraLooksForwardAlongTheBase) {
  CameraRigOptions rig;
  rig.pitch = 0;
  const Pose3 base_T_camera = rig.BaseTCamera();
  const Eigen::Matrix3d R = base_T_camera.RotationMatrix();
  EXPECT_TRUE(R.col(2).isApprox(Eigen::Vector3d::UnitX(), 1e-15));   // camera z = base x
  EXPECT_TRUE(R.col(0).isApprox(-Eigen::Vector3d::UnitY(), 1e-15));  // camera x = -base y
  EXPECT_TRUE(R.col(1).isApprox(-Eigen::Vector3d::UnitZ(), 1e-15));  // camera y = -base z
  EXPECT_NEAR(R.determinant(), 1.0, 1e-15);
  rig.pitch = 0.1;
  const Eigen::Vector3d axis = rig.BaseTCamera().rotation * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::atan2(-axis.z(), axis.x()), 0.1, 1e-15);  // pitched down by 0.1 rad
  EXPECT_NEAR(rig.BaseTCamera().RotationMatrix().determinant(), 1.0, 1e-15);
}

}  // namespace
}  // namespace sfm

// LoopCandidates (backend/initialization/loop_candidates.h): revisits found on the pose estimate,
// none where the camera went straight on or where the tracks already link the two frames.
#include "backend/initialization/loop_candidates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace sfm {
namespace {

constexpr int kWidth = 640, kHeight = 480;
constexpr int kFramesPerLap = 40;

Eigen::Matrix3d TestK() {
  Eigen::Matrix3d K;
  K << 450, 0, 319.5, 0, 450, 239.5, 0, 0, 1;
  return K;
}

// A camera at `centre` looking along the horizontal `forward`, image y down.
Pose3 LookingAlong(const Eigen::Vector3d& centre, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d z = forward.normalized(), y(0, 0, -1), x = y.cross(z);
  Eigen::Matrix3d R;
  R << x, y, z;
  return Pose3(R, centre);
}

bool Sees(const Pose3& world_T_camera, const Eigen::Vector3d& point) {
  const Eigen::Vector3d p = world_T_camera.Inverse() * point;
  if (p.z() < 0.1) return false;
  const Eigen::Vector3d x = TestK() * (p / p.z());
  return x.x() >= 0 && x.y() >= 0 && x.x() <= kWidth && x.y() <= kHeight;
}

// Points on a cylindrical wall of radius 4 m every 3 degrees at three heights.
std::vector<Eigen::Vector3d> CylinderWall() {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 120; ++k) {
    const double angle = k * M_PI / 60;
    for (double z : {-0.5, 0.0, 0.5}) points.emplace_back(4 * std::cos(angle), 4 * std::sin(angle), z);
  }
  return points;
}

// One landmark per wall point and lap (the tracks of two laps not linked) or per wall point (linked),
// observed from every frame of `cameras` that sees it.
Landmarks Observe(const std::vector<Pose3>& cameras, const std::vector<Eigen::Vector3d>& wall, bool linked) {
  Landmarks landmarks;
  const int laps = linked ? 1 : (static_cast<int>(cameras.size()) + kFramesPerLap - 1) / kFramesPerLap;
  for (int lap = 0; lap < laps; ++lap) {
    for (const Eigen::Vector3d& position : wall) {
      PointLandmark point;
      point.position = position;
      for (int f = 0; f < static_cast<int>(cameras.size()); ++f) {
        if (!linked && f / kFramesPerLap != lap) continue;
        if (Sees(cameras[f], position)) point.observations.push_back({f, 0, Eigen::Vector2d::Zero()});
      }
      if (!point.observations.empty()) landmarks.points.push_back(point);
    }
  }
  return landmarks;
}

// Two laps on a circle of radius 1 m, looking outwards at the wall.
std::vector<Pose3> TwoLaps() {
  std::vector<Pose3> cameras;
  for (int f = 0; f < 2 * kFramesPerLap; ++f) {
    const double angle = 2 * M_PI * f / kFramesPerLap;
    const Eigen::Vector3d radial(std::cos(angle), std::sin(angle), 0);
    cameras.push_back(LookingAlong(radial, radial));
  }
  return cameras;
}

// Two laps whose tracks are not linked: the candidates pair each frame of the second lap with one
// of the first that looks the same way (within 3 frames of a lap apart), each frame at most once,
// at most 80 / 6 = 13 of them.
TEST(LoopCandidatesTest, RevisitsOfASecondLapAreFound) {
  const std::vector<Pose3> cameras = TwoLaps();
  const std::vector<std::pair<int, int>> candidates =
      LoopCandidates(TestK(), kWidth, kHeight, cameras, Observe(cameras, CylinderWall(), /*linked=*/false));
  ASSERT_GE(candidates.size(), 10u);
  EXPECT_LE(candidates.size(), 13u);
  std::set<int> used;
  for (const auto& [a, b] : candidates) {
    EXPECT_LT(a, kFramesPerLap) << a << "-" << b;
    EXPECT_NEAR(b - a, kFramesPerLap, 3) << a << "-" << b;
    EXPECT_TRUE(used.insert(a).second) << a;
    EXPECT_TRUE(used.insert(b).second) << b;
  }
}

// The same laps with the tracks linked across them: nothing to close.
TEST(LoopCandidatesTest, FramesTheTracksAlreadyLinkAreNotCandidates) {
  const std::vector<Pose3> cameras = TwoLaps();
  EXPECT_TRUE(
      LoopCandidates(TestK(), kWidth, kHeight, cameras, Observe(cameras, CylinderWall(), /*linked=*/true)).empty());
}

// A camera driving straight along a wall, looking at it: frames far apart overlap little, and
// none is a revisit (the path between two frames is their distance).
TEST(LoopCandidatesTest, AStraightDriveHasNoCandidates) {
  std::vector<Pose3> cameras;
  for (int f = 0; f < 80; ++f) cameras.push_back(LookingAlong(Eigen::Vector3d(0.02 * f, 0, 0), Eigen::Vector3d(0, 1, 0)));
  std::vector<Eigen::Vector3d> wall;
  for (int k = 0; k < 200; ++k) {
    for (double z : {-0.5, 0.0, 0.5}) wall.emplace_back(-1 + 0.02 * k, 3, z);
  }
  // Tracks of 10 frames: every point again as a new landmark each 10 frames.
  Landmarks landmarks;
  for (int start = 0; start < 80; start += 10) {
    for (const Eigen::Vector3d& position : wall) {
      PointLandmark point;
      point.position = position;
      for (int f = start; f < start + 10; ++f) {
        if (Sees(cameras[f], position)) point.observations.push_back({f, 0, Eigen::Vector2d::Zero()});
      }
      if (!point.observations.empty()) landmarks.points.push_back(point);
    }
  }
  EXPECT_TRUE(LoopCandidates(TestK(), kWidth, kHeight, cameras, landmarks).empty());
  // The revisit test is what rejects them: without it, frames of different track windows overlap.
  LoopCandidateOptions no_revisit_test;
  no_revisit_test.min_path_over_distance = 0;
  EXPECT_FALSE(LoopCandidates(TestK(), kWidth, kHeight, cameras, landmarks, no_revisit_test).empty());
}

}  // namespace
}  // namespace sfm

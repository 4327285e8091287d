// The run's own evidence on a trajectory: the matches' epipolar fit, and the steps that leave the
// odometry beyond its noise.
#include "backend/initialization/trajectory_evidence.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/initialization/synthetic_drive.h"

namespace sfm {
namespace {

// Junctions of random points seen by every camera, matched between consecutive frames.
void SeenPoints(const Eigen::Matrix3d& K, const std::vector<Pose3>& world_T_camera, std::vector<Junctions>* frames,
                std::vector<FramePairMatches>* pairs) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::vector<Eigen::Vector3d> points_in_camera0;
  for (int k = 0; k < 60; ++k) points_in_camera0.emplace_back(2 * uniform(rng), uniform(rng), 6 + 2 * uniform(rng));
  frames->assign(world_T_camera.size(), Junctions());
  for (size_t f = 0; f < world_T_camera.size(); ++f) {
    const Pose3 camera_T_camera0 = world_T_camera[f].Inverse() * world_T_camera[0];
    for (size_t k = 0; k < points_in_camera0.size(); ++k) {
      const Eigen::Vector3d p = K * (camera_T_camera0 * points_in_camera0[k]);
      Junction junction;
      junction.id = static_cast<int>(k);
      junction.location = p.head<2>() / p.z();
      (*frames)[f].push_back(junction);
    }
  }
  for (size_t f = 0; f + 1 < world_T_camera.size(); ++f) {
    FramePairMatches pair;
    pair.frame_a = static_cast<int>(f);
    pair.frame_b = static_cast<int>(f + 1);
    for (int k = 0; k < 60; ++k) pair.matches.push_back(JunctionMatch{k, k, 1.0, 0, -1, -1});
    pairs->push_back(pair);
  }
}

TEST(TrajectoryEvidence, TheTruthFitsTheMatchesAndATurnedTrajectoryDoesNot) {
  Eigen::Matrix3d K;
  K << 450, 0, 319.5, 0, 450, 239.5, 0, 0, 1;
  const std::vector<Pose3> truth = TrueDrive(10, 0.02);
  std::vector<Pose3> cameras, turned;
  for (const Pose3& pose : truth) cameras.push_back(pose * TestBaseTCamera());
  // The same drive with 0.01 rad more heading per frame: the pairs' epipolar geometry is off.
  for (const Pose3& pose : TrueDrive(10, 0.03)) turned.push_back(pose * TestBaseTCamera());
  std::vector<Junctions> frames;
  std::vector<FramePairMatches> pairs;
  SeenPoints(K, cameras, &frames, &pairs);
  // Exact projections: zero to rounding. A 0.01 rad rotation moves a point by about 4.5 px at
  // f = 450; the Sampson distance of the median match is observed at 1.7 px; asserted above 1.
  EXPECT_LT(EpipolarEvidencePx(K, cameras, frames, pairs), 1e-6);
  EXPECT_GT(EpipolarEvidencePx(K, turned, frames, pairs), 1.0);
}

TEST(TrajectoryEvidence, TheStepThatTurnsBeyondTheNoiseIsFound) {
  const std::vector<Pose3> odometry = TrueDrive(10, 0.02);
  std::vector<Pose3> refined = odometry;
  // From frame 6 on, turned by 0.05 rad about the vertical: step 5 -> 6 departs by 0.05 rad.
  const Pose3 turn(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ())), Eigen::Vector3d::Zero());
  for (size_t k = 6; k < refined.size(); ++k) refined[k] = refined[5] * turn * (odometry[5].Inverse() * odometry[k]);
  OdometryNoise noise;
  noise.rotation_sigma = 0.01;  // 3 sigma: 0.03 rad < 0.05
  noise.translation_sigma = 0.05;
  EXPECT_EQ(FramesDisagreeingWithOdometry(odometry, refined, noise, 0.05), std::vector<int>({6}));
  EXPECT_TRUE(FramesDisagreeingWithOdometry(odometry, odometry, noise, 0.05).empty());
}

}  // namespace
}  // namespace sfm

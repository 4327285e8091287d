// MatchKeypoints and KeypointPairPoses on real images with ground truth: Strecha entry-P10
// imported at 768x512.
#include "frontend/keypoints/keypoint_pose.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "frontend/batch/sequence_frontend.h"
#include "frontend/sequence/sequence.h"
#include "tests/keypoints/strecha_entry.h"
#include "tests/test_cameras.h"

namespace sfm {
namespace {

// Figures protected, on consecutive pairs 0-1, 4-5 and 8-9 with three times the importer's default
// odometry noise: the keypoints' pose (KeypointPairPoses) is within 0.6 deg of the true rotation and
// closer to it than the odometry's (measured 0.11, 0.22, 0.35 deg against 0.71, 1.85, 0.86), and
// the translation keeps about the odometry's length.
TEST(KeypointPoseTest, StrechaEntryP10PosesRefinedUnderTheOdometry) {
  const std::string out = testing::ImportStrechaEntryAtThreeTimesTheNoise("keypoint_pose_entry");
  if (out.empty()) GTEST_SKIP() << "../shared/data/strecha-entry-P10 is absent";
  Sequence sequence;
  ASSERT_TRUE(ReadSequence(out, &sequence).ok());
  const Camera& camera = sequence.calibration.camera;
  std::vector<FrameKeypoints> keypoints;
  for (int frame = 0; frame < static_cast<int>(sequence.frames.size()); ++frame) {
    cv::Mat image;
    ASSERT_TRUE(LoadFrameImage(sequence, frame, &image).ok());
    keypoints.push_back(DetectKeypoints(image, camera));
  }
  const std::vector<std::pair<int, int>> pairs = {{0, 1}, {4, 5}, {8, 9}};
  std::vector<PairGeometry> geometries;
  for (const auto& [a, b] : pairs) {
    geometries.push_back(PairGeometryFromOdometry(
        camera.K(), sequence.calibration.base_T_camera, sequence.frames[a].world_T_base_odometry,
        sequence.frames[b].world_T_base_odometry, sequence.calibration.odometry_noise.translation_sigma,
        sequence.calibration.odometry_noise.rotation_sigma, b - a));
  }
  const std::vector<std::optional<Pose3>> refined =
      KeypointPairPoses(geometries, MatchConsecutiveKeypoints(pairs, keypoints), PairRefinementSettings());
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto [a, b] = pairs[p];
    const Pose3 camera_a = *sequence.frames[a].world_T_base_groundtruth * sequence.calibration.base_T_camera;
    const Pose3 camera_b = *sequence.frames[b].world_T_base_groundtruth * sequence.calibration.base_T_camera;
    const Pose3 truth = camera_b.Inverse() * camera_a;
    ASSERT_TRUE(refined[p].has_value()) << "pair " << a;
    const double refined_deg = RotationAngle(refined[p]->rotation, truth.rotation) * 180 / M_PI;
    const double odometry_deg = RotationAngle(geometries[p].camera2_T_camera1.rotation, truth.rotation) * 180 / M_PI;
    std::cout << "[ figure   ] pair " << a << "-" << b << ": rotation off the truth by " << refined_deg
              << " deg (odometry " << odometry_deg << ")\n";
    EXPECT_LT(refined_deg, 0.6) << "pair " << a;
    EXPECT_LT(refined_deg, odometry_deg) << "pair " << a;
    EXPECT_NEAR(refined[p]->translation.norm(), geometries[p].camera2_T_camera1.translation.norm(),
                0.2 * geometries[p].camera2_T_camera1.translation.norm());
  }
}

// A frame without texture gives no keypoints and so no pose, not a made-up one.
TEST(KeypointPoseTest, UniformImagesGiveNoPose) {
  const Camera camera = testing::BenchmarkLens();
  const cv::Mat grey(camera.height, camera.width, CV_8UC1, cv::Scalar(128));
  const FrameKeypoints keypoints = DetectKeypoints(grey, camera);
  EXPECT_TRUE(keypoints.locations.empty());
  EXPECT_TRUE(MatchKeypoints(keypoints, keypoints).x1.empty());
  PairGeometry geometry;
  geometry.K = camera.K();
  geometry.camera2_T_camera1.translation = Eigen::Vector3d(-1, 0, 0);
  geometry.covariance.diagonal().setConstant(1e-4);
  EXPECT_FALSE(KeypointPairPoses({geometry}, MatchConsecutiveKeypoints({{0, 1}}, {keypoints, keypoints}),
                                 PairRefinementSettings())[0]
                   .has_value());
}

}  // namespace
}  // namespace sfm

#include "benchmarks/colmap_ate/colmap_poses.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;

// A curved path of 6 camera poses world_T_camera.
std::vector<Pose3> TruePath() {
  std::vector<Pose3> path;
  for (int i = 0; i < 6; ++i) {
    path.emplace_back(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * i, Eigen::Vector3d(0.1, 1, 0.2).normalized())),
        Eigen::Vector3d(std::sin(0.5 * i), 0.1 * i * i, 0.7 * i));
  }
  return path;
}

// images.txt as COLMAP writes it, of the poses colmap_S_world * world_T_camera (a similarity: COLMAP's
// world has its own frame and scale), frames 0..5 but frame 3 not registered; frame 4 has no 2D point
// (an empty line).
void WriteImagesTxt(const fs::path& path, const std::vector<Pose3>& world_T_camera, double scale,
                    const Pose3& colmap_T_world) {
  std::ofstream out(path);
  out << "# Image list with two lines of data per image:\n#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, "
         "CAMERA_ID, NAME\n"
      << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n# Number of images: 5, mean observations per image: 1\n";
  for (int i = 0; i < 6; ++i) {
    if (i == 3) continue;
    Pose3 colmap_T_camera = colmap_T_world * world_T_camera[i];
    colmap_T_camera.translation =
        colmap_T_world.rotation * (scale * world_T_camera[i].translation) + colmap_T_world.translation;
    const Pose3 camera_T_colmap = colmap_T_camera.Inverse();
    const Eigen::Quaterniond& q = camera_T_colmap.rotation;
    const Eigen::Vector3d& t = camera_T_colmap.translation;
    out.precision(17);
    out << i + 10 << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " " << t.x() << " "
        << t.y() << " " << t.z() << " 1 "
        << "00000" << i << ".png\n";
    out << (i == 4 ? "" : "12.5 40.25 -1 100.0 20.0 7") << "\n";
  }
}

// COLMAP's world_T_camera is recovered from its camera_T_world lines (1e-12), and a similarity copy
// of the truth with one frame unregistered has a Sim(3) ATE of 0 (1e-9) over the 5 registered frames,
// scale 1 / 2.5, and a rigid ATE well above 0 (the scale is not taken out).
TEST(ColmapPosesTest, ReadsCameraPosesAndMeasuresTheRegisteredFrames) {
  const fs::path scratch = testing::MakeScratchDir("colmap_poses");
  const std::vector<Pose3> truth = TruePath();
  const Pose3 colmap_T_world(
      Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, -2, 0.5).normalized())),
      Eigen::Vector3d(3, -1, 2));
  WriteImagesTxt(scratch / "images.txt", truth, 2.5, colmap_T_world);
  std::map<std::string, Pose3> by_name;
  const Status status = ReadColmapImagePoses((scratch / "images.txt").string(), &by_name);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(by_name.size(), 5u);
  ASSERT_TRUE(by_name.count("000005.png"));
  const Pose3 expected = colmap_T_world * truth[5];
  EXPECT_LT(RotationAngle(by_name["000005.png"].rotation, expected.rotation), 1e-12);

  Sequence sequence;
  sequence.directory = scratch.string();
  sequence.has_groundtruth = true;
  for (int i = 0; i < 6; ++i) {
    Frame frame;
    frame.index = i;
    frame.world_T_base_groundtruth = truth[i];
    sequence.frames.push_back(frame);
  }
  std::map<int, Pose3> by_frame;
  for (int i = 0; i < 6; ++i) {
    const std::string name = "00000" + std::to_string(i) + ".png";
    if (by_name.count(name)) by_frame[i] = by_name[name];
  }
  FrameSubsetDrift drift;
  ASSERT_TRUE(ComputeFrameSubsetDrift(sequence, by_frame, &drift).ok());
  EXPECT_EQ(drift.frames, 6);
  EXPECT_EQ(drift.registered, (std::vector<int>{0, 1, 2, 4, 5}));
  EXPECT_LT(drift.ate_sim3_m, 1e-9);
  EXPECT_NEAR(drift.sim3_scale, 1 / 2.5, 1e-9);
  EXPECT_GT(drift.ate_m, 0.5);
}

// A malformed image line and a missing file fail naming the file (and line).
TEST(ColmapPosesTest, BadFilesNameTheFileAndLine) {
  const fs::path scratch = testing::MakeScratchDir("colmap_poses_bad");
  std::map<std::string, Pose3> by_name;
  Status status = ReadColmapImagePoses((scratch / "absent.txt").string(), &by_name);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("absent.txt"), std::string::npos);
  std::ofstream(scratch / "images.txt") << "# header\n1 1 0 0 0 1 2 3 1 a.png\n\n2 1 0 0 x 1 2 3 1 b.png\n\n";
  status = ReadColmapImagePoses((scratch / "images.txt").string(), &by_name);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("images.txt:4:"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace sfm

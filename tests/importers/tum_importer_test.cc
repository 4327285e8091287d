#include "sequences/importers/tum_importer.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "frontend/sequence/sequence.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kStart = 1305031102.0;  // a TUM-like Unix time

// The true motion: constant velocity and constant angular rate about a fixed axis, so that linear
// interpolation and slerp between any two samples are exact.
Pose3 TruePose(double t) {
  const double s = t - kStart;
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.2 + 0.8 * s, Eigen::Vector3d(0.3, 1, -0.2).normalized())),
               Eigen::Vector3d(0.5 + 0.9 * s, -0.2 * s, 1.4 + 0.1 * s));
}

std::string Stamp(double seconds_after_start) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6f", kStart + seconds_after_start);
  return text;
}

// rgb.txt lists 6 images: before the ground truth, between two samples, on a sample, in a gap of
// 0.14 s, between two samples, after the ground truth.
fs::path WriteTumFolder(const std::string& name) {
  const fs::path dir = testing::MakeScratchDir(name);
  fs::create_directories(dir / "rgb");
  std::string list = "# color images\n# file: 'fake'\n# timestamp filename\n";
  cv::Mat image(480, 640, CV_8UC3);
  for (double t : {0.175304, 0.211214, 0.25, 0.3, 0.42, 0.6}) {
    const std::string file = "rgb/" + Stamp(t) + ".png";
    image.setTo(cv::Scalar(100 * t, 50, 200 * t));
    cv::imwrite((dir / file).string(), image);
    list += Stamp(t) + " " + file + "\n";
  }
  std::ofstream(dir / "rgb.txt") << list;
  std::ofstream truth(dir / "groundtruth.txt");
  truth << "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n";
  truth.precision(17);
  for (double t : {0.2, 0.21, 0.22, 0.25, 0.26, 0.4, 0.41, 0.43}) {
    const Pose3 pose = TruePose(kStart + t);
    truth << Stamp(t) << " " << pose.translation.x() << " " << pose.translation.y() << " " << pose.translation.z()
          << " " << pose.rotation.x() << " " << pose.rotation.y() << " " << pose.rotation.z() << " "
          << pose.rotation.w() << "\n";
  }
  return dir;
}

TEST(TumImporterTest, InterpolatesGroundTruthAndSkipsImagesWithoutIt) {
  const fs::path dir = WriteTumFolder("tum_folder");
  TumImportOptions options;
  options.camera = TumCamera::kFreiburg1;
  ImportedSequence sequence;
  const Status status = ReadTumSequence(dir.string(), options, &sequence);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(sequence.frames.size(), 3u);  // 0.211214, 0.25 and 0.42
  const double expected_times[] = {0.211214, 0.25, 0.42};
  for (size_t i = 0; i < 3; ++i) {
    const ImportedFrame& frame = sequence.frames[i];
    EXPECT_EQ(frame.timestamp, std::stod(Stamp(expected_times[i])));
    const Pose3 truth = TruePose(frame.timestamp);
    // Timestamps near 1.3e9 s carry ~1e-7 s of rounding: interpolation is exact to ~1e-7.
    EXPECT_LT((frame.world_T_camera.translation - truth.translation).norm(), 1e-6) << i;
    EXPECT_LT(RotationAngle(frame.world_T_camera.rotation, truth.rotation), 1e-6) << i;
  }
  EXPECT_EQ(sequence.camera.fx, 517.306408);
  EXPECT_EQ(sequence.camera.distortion[4], 1.163314);

  // Written and read back as a SPEC sequence: Unix-time timestamps associate exactly.
  const fs::path out = dir / "sequence";
  ASSERT_TRUE(WriteImportedSequence(sequence, SequenceWriteOptions(), out.string()).ok());
  Sequence read;
  const Status read_status = ReadSequence(out.string(), &read);
  ASSERT_TRUE(read_status.ok()) << read_status.message();
  ASSERT_EQ(read.frames.size(), 3u);
  EXPECT_EQ(read.frames[2].timestamp, sequence.frames[2].timestamp);
  EXPECT_EQ(read.calibration.camera.width, 640);  // narrower than max_width: not scaled
  EXPECT_EQ(read.calibration.camera.distortion[0], 0.262383);
  EXPECT_TRUE(read.calibration.base_T_camera.translation.isZero());
  EXPECT_LT((read.frames[1].world_T_base_groundtruth->translation - TruePose(read.frames[1].timestamp).translation).norm(),
            1e-6);
  EXPECT_TRUE(read.calibration.odometry_noise_given);
}

TEST(TumImporterTest, StrideAndCameraChoice) {
  const fs::path dir = WriteTumFolder("tum_stride");
  TumImportOptions options;
  options.stride = 2;
  ASSERT_TRUE(ParseTumCamera("fr3", &options.camera).ok());
  ImportedSequence sequence;
  ASSERT_TRUE(ReadTumSequence(dir.string(), options, &sequence).ok());
  ASSERT_EQ(sequence.frames.size(), 2u);  // the 1st and 3rd of the three with ground truth
  EXPECT_EQ(sequence.frames[1].timestamp, std::stod(Stamp(0.42)));
  EXPECT_EQ(sequence.camera.fx, 535.4);
  EXPECT_FALSE(sequence.camera.HasDistortion());
  EXPECT_THAT(ParseTumCamera("fr4", &options.camera).message(), HasSubstr("unknown TUM camera 'fr4'"));
}

TEST(TumImporterTest, InterpolatePoseEnds) {
  const Pose3 a = TruePose(kStart), b = TruePose(kStart + 1);
  EXPECT_LT((InterpolatePose(a, b, 0).translation - a.translation).norm(), 1e-15);
  EXPECT_LT(RotationAngle(InterpolatePose(a, b, 1).rotation, b.rotation), 1e-12);
  EXPECT_LT(RotationAngle(InterpolatePose(a, b, 0.5).rotation, TruePose(kStart + 0.5).rotation), 1e-12);
}

void ExpectError(const fs::path& dir, const std::string& file, const std::string& problem) {
  ImportedSequence sequence;
  const Status status = ReadTumSequence(dir.string(), TumImportOptions(), &sequence);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(file));
  EXPECT_THAT(status.message(), HasSubstr(problem));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
}

TEST(TumImporterTest, BadInputsGiveOneLineErrors) {
  const fs::path dir = WriteTumFolder("tum_bad");
  const std::string list = (dir / "rgb.txt").string();
  std::ofstream(list) << "# timestamp filename\n" << Stamp(0.21) << " rgb/a.png extra\n";
  ExpectError(dir, "rgb.txt:2", "expected '<timestamp> <image file>'");
  std::ofstream(list) << Stamp(0.25) << " rgb/" << Stamp(0.25) << ".png\n" << Stamp(0.211214) << " rgb/b.png\n";
  ExpectError(dir, "rgb.txt:2", "is not after the previous line's");
  std::ofstream(list) << Stamp(0.211214) << " rgb/missing.png\n";
  ExpectError(dir, "rgb.txt:1", "missing.png does not exist");
  std::ofstream(list) << Stamp(0.6) << " rgb/" << Stamp(0.6) << ".png\n";
  ExpectError(dir, "rgb.txt", "only 0 image(s) have ground truth (1 outside its time span, 0 in gaps)");
  std::ofstream(dir / "groundtruth.txt") << Stamp(0.2) << " 0 0 0 0 0 0\n";
  ExpectError(dir, "groundtruth.txt:1", "");
  fs::remove(dir / "groundtruth.txt");
  ExpectError(dir, "groundtruth.txt", "file does not exist");
  fs::remove(list);
  ExpectError(dir, "rgb.txt", "file does not exist");
  ExpectError(dir / "absent", "absent", "input directory does not exist");
}

}  // namespace
}  // namespace sfm

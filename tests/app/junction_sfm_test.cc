// junction_sfm as a user runs it: exit status, the one-line error on bad input, and no output
// written when the input is bad (SPEC section 2).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 64, kHeight = 48;

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

using testing::ReadFile;

// A valid three-frame sequence: small images, odometry moving forward, ground truth equal to it.
void WriteValidSequence(const fs::path& dir) {
  fs::create_directories(dir / "images");
  WriteText(dir / "sequence.yaml",
            "%YAML:1.0\n---\n"
            "image_width: 64\nimage_height: 48\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
            "   data: [ 50., 0., 32., 0., 50., 24., 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
            "   data: [ 0., 0., 0., 0., 0. ]\n"
            "T_base_camera: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
            "   data: [ 0., 0., 1., 0., -1., 0., 0., 0., 0., -1., 0., 1., 0., 0., 0., 1. ]\n");
  std::string images = "# timestamp path\n", odometry = "# timestamp tx ty tz qx qy qz qw\n";
  for (int i = 0; i < 3; ++i) {
    const std::string name = "images/00000" + std::to_string(i) + ".png";
    cv::Mat image(kHeight, kWidth, CV_8UC1, cv::Scalar(40 + 50 * i));
    cv::imwrite((dir / name).string(), image);
    images += std::to_string(i * 0.1) + " " + name + "\n";
    odometry += std::to_string(i * 0.1) + " " + std::to_string(0.2 * i) + " 0 0 0 0 0 1\n";
  }
  WriteText(dir / "images.txt", images);
  WriteText(dir / "odometry.txt", odometry);
  WriteText(dir / "groundtruth.txt", odometry);
}

struct RunResult {
  int exit_code = -1;
  std::string stderr_text;
};

RunResult RunJunctionSfm(const std::string& arguments, const fs::path& scratch) {
  const std::string binary = SFM_JUNCTION_SFM_BINARY;
  const fs::path err = scratch / "stderr.txt";
  const std::string command = binary + " --progress=false --minloglevel=2 " + arguments + " > /dev/null 2> " +
                              err.string();
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.stderr_text = ReadFile(err);
  return result;
}

class JunctionSfmBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = testing::MakeScratchDir(std::string("app_") +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    sequence_ = scratch_ / "sequence";
    output_ = scratch_ / "output";
    WriteValidSequence(sequence_);
  }

  // Runs on the (broken) sequence and checks the contract for bad input: non-zero exit, exactly
  // one line on stderr that holds every expected fragment, and no output file written.
  void ExpectOneLineError(const std::vector<std::string>& fragments) {
    const RunResult result =
        RunJunctionSfm("--sequence=" + sequence_.string() + " --output=" + output_.string(), scratch_);
    EXPECT_NE(result.exit_code, 0);
    ASSERT_FALSE(result.stderr_text.empty());
    EXPECT_EQ(result.stderr_text.find('\n'), result.stderr_text.size() - 1)
        << "expected one line, got: " << result.stderr_text;
    for (const std::string& fragment : fragments) EXPECT_THAT(result.stderr_text, HasSubstr(fragment));
    EXPECT_TRUE(!fs::exists(output_) || fs::is_empty(output_)) << "output written despite bad input";
  }

  fs::path scratch_, sequence_, output_;
};

TEST_F(JunctionSfmBadInput, ValidSequenceRunsAndWritesTrajectories) {
  const RunResult result =
      RunJunctionSfm("--sequence=" + sequence_.string() + " --output=" + output_.string(), scratch_);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_TRUE(fs::exists(output_ / "trajectory_odometry.txt"));
  EXPECT_TRUE(fs::exists(output_ / "trajectory_groundtruth.txt"));
  EXPECT_TRUE(fs::exists(output_ / "metrics.json"));
  EXPECT_THAT(ReadFile(output_ / "metrics.json"), HasSubstr("\"frames\": 3"));
}

TEST_F(JunctionSfmBadInput, MissingDirectory) {
  fs::remove_all(sequence_);
  ExpectOneLineError({sequence_.string()});
}

TEST_F(JunctionSfmBadInput, EmptyImagesTxt) {
  WriteText(sequence_ / "images.txt", "# nothing\n");
  ExpectOneLineError({"images.txt"});
}

TEST_F(JunctionSfmBadInput, ImageThatDoesNotDecode) {
  WriteText(sequence_ / "images/000001.png", "this is not a PNG");
  ExpectOneLineError({"000001.png"});
}

TEST_F(JunctionSfmBadInput, ImageOfTheWrongSize) {
  cv::imwrite((sequence_ / "images/000002.png").string(), cv::Mat(kHeight + 1, kWidth, CV_8UC1, cv::Scalar(0)));
  ExpectOneLineError({"000002.png", "64x48"});
}

TEST_F(JunctionSfmBadInput, YamlWithMissingKey) {
  std::string yaml = ReadFile(sequence_ / "sequence.yaml");
  yaml.replace(yaml.find("image_width: 64\n"), 16, "");
  WriteText(sequence_ / "sequence.yaml", yaml);
  ExpectOneLineError({"sequence.yaml", "image_width"});
}

TEST_F(JunctionSfmBadInput, YamlWithMalformedKey) {
  std::string yaml = ReadFile(sequence_ / "sequence.yaml");
  yaml.replace(yaml.find("rows: 3\n   cols: 3"), 18, "rows: 2\n   cols: 3");
  yaml.replace(yaml.find("50., 0., 32., 0., 50., 24., 0., 0., 1."), 38, "50., 0., 32., 0., 50., 24.");
  WriteText(sequence_ / "sequence.yaml", yaml);
  ExpectOneLineError({"sequence.yaml", "camera_matrix"});
}

TEST_F(JunctionSfmBadInput, YamlThatIsNotYaml) {
  WriteText(sequence_ / "sequence.yaml", "%YAML:1.0\n---\nimage_width: [1, 2\n  : : :\n");
  ExpectOneLineError({"sequence.yaml"});
}

TEST_F(JunctionSfmBadInput, OdometryLineWithTooFewNumbers) {
  WriteText(sequence_ / "odometry.txt", "0.0 0 0 0 0 0 0 1\n0.1 0.2 0 0 0 0 1\n0.2 0.4 0 0 0 0 0 1\n");
  ExpectOneLineError({"odometry.txt:2"});
}

TEST_F(JunctionSfmBadInput, OdometryWithNaN) {
  WriteText(sequence_ / "odometry.txt", "0.0 0 0 0 0 0 0 1\n0.1 nan 0 0 0 0 0 1\n0.2 0.4 0 0 0 0 0 1\n");
  ExpectOneLineError({"odometry.txt:2"});
}

// Finite but absurd odometry overflows the pair geometry (its covariance squares the
// coordinates); before session 8 this aborted in the matcher's CHECK with exit 134.
TEST_F(JunctionSfmBadInput, OdometryTooLargeForAFiniteRelativeMotion) {
  WriteText(sequence_ / "odometry.txt", "0.0 0 0 0 0 0 0 1\n0.1 1e160 0 0 0 0 0 1\n0.2 0.4 0 0 0 0 0 1\n");
  ExpectOneLineError({"odometry.txt", "finite relative motion"});
}

TEST_F(JunctionSfmBadInput, TimestampsOutOfOrder) {
  WriteText(sequence_ / "images.txt",
            "0.0 images/000000.png\n0.2 images/000002.png\n0.1 images/000001.png\n");
  ExpectOneLineError({"images.txt:3"});
}

TEST_F(JunctionSfmBadInput, FewerThanTwoFrames) {
  WriteText(sequence_ / "images.txt", "0.0 images/000000.png\n");
  ExpectOneLineError({"images.txt"});
}

TEST_F(JunctionSfmBadInput, OutputDirectoryThatCannotBeWritten) {
  WriteText(scratch_ / "a_file", "x");  // a directory cannot be made inside a regular file
  output_ = scratch_ / "a_file" / "output";
  ExpectOneLineError({output_.string()});
}

// A flag value that is not one of the choices: exit 2, one line naming the flag, nothing written.
// The other values run.
TEST_F(JunctionSfmBadInput, BundleAdjustmentChoiceFlags) {
  const std::string io = "--sequence=" + sequence_.string() + " --output=" + output_.string();
  const RunResult bad = RunJunctionSfm(io + " --floor_prior=sometimes", scratch_);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.stderr_text, HasSubstr("--floor_prior must be 'auto', 'on' or 'off'"));
  EXPECT_TRUE(!fs::exists(output_) || fs::is_empty(output_));
  const RunResult bad_bias = RunJunctionSfm(io + " --odometry_rotation_bias=some", scratch_);
  EXPECT_EQ(bad_bias.exit_code, 2);
  EXPECT_THAT(bad_bias.stderr_text, HasSubstr("--odometry_rotation_bias must be 'on', 'off' or 'auto'"));
  for (const std::string flags : {"--floor_prior=on", "--floor_prior=off --odometry_rotation_bias=on"}) {
    const RunResult result = RunJunctionSfm(io + " " + flags, scratch_);
    EXPECT_EQ(result.exit_code, 0) << flags << ": " << result.stderr_text;
    EXPECT_TRUE(fs::exists(output_ / "metrics.json")) << flags;
  }
}

}  // namespace
}  // namespace sfm

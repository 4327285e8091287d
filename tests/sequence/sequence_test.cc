#include "frontend/sequence/sequence.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "frontend/geometry/tum_io.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr int kWidth = 64;
constexpr int kHeight = 48;

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

Calibration TestCalibration() {
  Calibration calibration;
  Camera& camera = calibration.camera;
  camera.width = kWidth;
  camera.height = kHeight;
  camera.fx = 50.25;
  camera.fy = 49.75;
  camera.cx = 31.5;
  camera.cy = 23.5;
  camera.distortion = {-0.3, 0.1, 1e-3, -1e-3, -0.02};
  calibration.base_T_camera =
      Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized())),
            Eigen::Vector3d(0.1, -0.2, 1.0 / 3));
  calibration.odometry_noise = {0.03, 0.002};
  calibration.odometry_noise_given = true;
  return calibration;
}

std::string OpenCvMatrix(int rows, int cols, const std::string& data) {
  return "!!opencv-matrix\n   rows: " + std::to_string(rows) + "\n   cols: " + std::to_string(cols) +
         "\n   dt: d\n   data: [ " + data + " ]";
}

// A valid sequence.yaml as key -> value text, so a test can change or drop one key.
std::map<std::string, std::string> ValidYamlKeys() {
  return {{"image_width", "64"},
          {"image_height", "48"},
          {"camera_matrix", OpenCvMatrix(3, 3, "50, 0, 31.5, 0, 50, 23.5, 0, 0, 1")},
          {"distortion_coefficients", OpenCvMatrix(1, 5, "-0.1, 0.01, 0, 0, 0")},
          {"T_base_camera", OpenCvMatrix(4, 4, "0, 0, 1, 0.1, -1, 0, 0, 0, 0, -1, 0, 0.5, 0, 0, 0, 1")}};
}

std::string YamlText(const std::map<std::string, std::string>& keys) {
  std::string text = "%YAML:1.0\n---\n";
  for (const auto& [key, value] : keys) text += key + ": " + value + "\n";
  return text;
}

// A valid three-frame sequence in a scratch directory; each test breaks one thing in it.
// Odometry has more lines than images and is offset by up to 0.9 ms, to exercise association.
class SequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeScratchDir(std::string("sequence_") +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    ASSERT_TRUE(WriteCalibration(Path("sequence.yaml"), TestCalibration()).ok());
    std::filesystem::create_directories(Path("images"));
    cv::Mat grey(kHeight, kWidth, CV_8UC1), colour(kHeight, kWidth, CV_8UC3);
    cv::randu(grey, 0, 255);
    cv::randu(colour, 0, 255);
    ASSERT_TRUE(cv::imwrite(Path("images/000000.png"), grey));
    ASSERT_TRUE(cv::imwrite(Path("images/000001.png"), colour));
    ASSERT_TRUE(cv::imwrite(Path("images/000002.png"), grey));
    WriteText(Path("images.txt"),
              "# timestamp image\n10.0 images/000000.png\n\n10.1 images/000001.png  # colour\n"
              "10.2 images/000002.png\n");
    WriteText(Path("odometry.txt"),
              "# timestamp tx ty tz qx qy qz qw\n9.95 9.95 0 0 0 0 0 1\n10.0004 10.0004 0 0 0 0 0 1\n"
              "10.05 10.05 0 0 0 0 0 1\n10.1 10.1 0 0 0 0 0 1\n10.15 10.15 0 0 0 0 0 1\n"
              "10.2009 10.2009 0 0 0 0 0 1\n");
    WriteText(Path("groundtruth.txt"), "10.0 0 1 0 0 0 0 1\n10.1 0 2 0 0 0 0 1\n10.2 0 3 0 0 0 0 1\n");
  }

  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  Status Read() { return ReadSequence(dir_, &sequence_); }

  // The status failed with one line holding every expected piece (file, line, problem).
  static void ExpectError(const Status& status, const std::vector<std::string>& pieces) {
    ASSERT_FALSE(status.ok());
    for (const std::string& piece : pieces) EXPECT_THAT(status.message(), HasSubstr(piece));
    EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
  }

  void ExpectYamlError(const std::map<std::string, std::string>& keys, const std::vector<std::string>& pieces) {
    WriteText(Path("sequence.yaml"), YamlText(keys));
    std::vector<std::string> with_file = pieces;
    with_file.push_back(Path("sequence.yaml"));
    ExpectError(Read(), with_file);
  }

  std::string dir_;
  Sequence sequence_;
};

// --- What a valid sequence gives ----------------------------------------------------------------

TEST_F(SequenceTest, ReadsValidSequenceAndAssociatesNearestPoseWithin1ms) {
  const Status status = Read();
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(sequence_.frames.size(), 3u);
  EXPECT_TRUE(sequence_.has_groundtruth);
  const double expected_odometry_x[] = {10.0004, 10.1, 10.2009};
  for (int i = 0; i < 3; ++i) {
    const Frame& frame = sequence_.frames[i];
    EXPECT_EQ(frame.index, i);
    EXPECT_EQ(frame.image_path, "images/00000" + std::to_string(i) + ".png");
    EXPECT_EQ(frame.world_T_base_odometry.translation.x(), expected_odometry_x[i]);
    ASSERT_TRUE(frame.world_T_base_groundtruth.has_value());
    EXPECT_EQ(frame.world_T_base_groundtruth->translation.y(), i + 1.0);
  }
  EXPECT_EQ(sequence_.frames[1].timestamp, 10.1);
}

TEST_F(SequenceTest, UnixTimestampsExactly1msApartAreAssociated) {
  // At 1.6e9 s a double resolves ~2e-7 s, so "1 ms" read from text is not exactly 1e-3.
  WriteText(Path("images.txt"), "1600000000.100 images/000000.png\n1600000000.200 images/000001.png\n");
  WriteText(Path("odometry.txt"), "1600000000.101 0 0 0 0 0 0 1\n1600000000.199 0 0 0 0 0 0 1\n");
  WriteText(Path("groundtruth.txt"), "1600000000.099 0 0 0 0 0 0 1\n1600000000.201 0 0 0 0 0 0 1\n");
  const Status status = Read();
  EXPECT_TRUE(status.ok()) << status.message();
}

TEST_F(SequenceTest, WithoutGroundtruthFramesHaveNone) {
  std::filesystem::remove(Path("groundtruth.txt"));
  ASSERT_TRUE(Read().ok());
  EXPECT_FALSE(sequence_.has_groundtruth);
  for (const Frame& frame : sequence_.frames) EXPECT_FALSE(frame.world_T_base_groundtruth.has_value());
}

TEST_F(SequenceTest, CalibrationWriteThenReadRoundTripIsBitExact) {
  const Calibration written = TestCalibration();
  Calibration read;
  const Status status = ReadCalibration(Path("sequence.yaml"), &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.camera.width, written.camera.width);
  EXPECT_EQ(read.camera.height, written.camera.height);
  EXPECT_EQ(read.camera.K(), written.camera.K());
  EXPECT_EQ(read.camera.distortion, written.camera.distortion);
  // The rotation goes through a matrix, so it comes back to rounding, not bit for bit.
  EXPECT_LT(RotationAngle(read.base_T_camera.rotation, written.base_T_camera.rotation), 1e-15);
  EXPECT_EQ(read.base_T_camera.translation, written.base_T_camera.translation);
  EXPECT_TRUE(read.odometry_noise_given);
  EXPECT_EQ(read.odometry_noise.translation_sigma, 0.03);
  EXPECT_EQ(read.odometry_noise.rotation_sigma, 0.002);
}

TEST_F(SequenceTest, HandWrittenYamlWithoutDirectiveReadsWithDefaultNoise) {
  std::string text = YamlText(ValidYamlKeys());
  text.erase(0, text.find('\n') + 1);  // drop "%YAML:1.0"
  WriteText(Path("sequence.yaml"), text);
  Calibration calibration;
  const Status status = ReadCalibration(Path("sequence.yaml"), &calibration);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(calibration.camera.fx, 50);
  EXPECT_EQ(calibration.camera.distortion[0], -0.1);
  EXPECT_EQ(calibration.base_T_camera.translation, Eigen::Vector3d(0.1, 0, 0.5));
  EXPECT_FALSE(calibration.odometry_noise_given);
  EXPECT_EQ(calibration.odometry_noise.translation_sigma, OdometryNoise().translation_sigma);
}

TEST_F(SequenceTest, LoadFrameImageGivesGreyOfCalibratedSizeFromColour) {
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  const Status status = LoadFrameImage(sequence_, 1, &grey);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.size(), cv::Size(kWidth, kHeight));
}

// --- One test per bad input: the message names the file (and line) and the problem --------------

TEST_F(SequenceTest, MissingDirectoryFails) {
  ExpectError(ReadSequence(Path("no_such_dir"), &sequence_), {Path("no_such_dir"), "does not exist"});
}

TEST_F(SequenceTest, MissingSequenceYamlFails) {
  std::filesystem::remove(Path("sequence.yaml"));
  ExpectError(Read(), {Path("sequence.yaml"), "calibration file does not exist"});
}

TEST_F(SequenceTest, MalformedYamlFailsWithLine) {
  WriteText(Path("sequence.yaml"), "%YAML:1.0\n---\nimage_width: [64, 48\n");
  ExpectError(Read(), {Path("sequence.yaml") + ":3: malformed YAML"});
}

TEST_F(SequenceTest, EmptyYamlFails) {
  WriteText(Path("sequence.yaml"), "\n");
  ExpectError(Read(), {Path("sequence.yaml"), "file is empty"});
}

TEST_F(SequenceTest, MissingKeyFails) {
  auto keys = ValidYamlKeys();
  keys.erase("distortion_coefficients");
  ExpectYamlError(keys, {"missing key 'distortion_coefficients'"});
}

TEST_F(SequenceTest, CameraMatrixOfWrongShapeFails) {
  auto keys = ValidYamlKeys();
  keys["camera_matrix"] = OpenCvMatrix(2, 3, "50, 0, 31.5, 0, 50, 23.5");
  ExpectYamlError(keys, {"key 'camera_matrix' must be 3x3, found 2x3"});
}

TEST_F(SequenceTest, CameraMatrixThatIsNotAMatrixFails) {
  auto keys = ValidYamlKeys();
  keys["camera_matrix"] = "50";
  ExpectYamlError(keys, {"key 'camera_matrix' must be a 3x3 !!opencv-matrix"});
}

TEST_F(SequenceTest, MatrixDataOfWrongLengthFails) {
  auto keys = ValidYamlKeys();
  keys["distortion_coefficients"] = OpenCvMatrix(1, 5, "-0.1, 0.01");
  ExpectYamlError(keys, {"key 'distortion_coefficients' is not a valid !!opencv-matrix"});
}

TEST_F(SequenceTest, NonIntegerImageWidthFails) {
  auto keys = ValidYamlKeys();
  keys["image_width"] = "64.5";
  ExpectYamlError(keys, {"key 'image_width' must be an integer"});
}

TEST_F(SequenceTest, NonPositiveImageHeightFails) {
  auto keys = ValidYamlKeys();
  keys["image_height"] = "0";
  ExpectYamlError(keys, {"key 'image_height' must be positive, found 0"});
}

TEST_F(SequenceTest, NonFiniteNumberFails) {
  auto keys = ValidYamlKeys();
  keys["camera_matrix"] = OpenCvMatrix(3, 3, "50, 0, .nan, 0, 50, 23.5, 0, 0, 1");
  ExpectYamlError(keys, {"key 'camera_matrix' entry (0,2) is not finite"});
}

TEST_F(SequenceTest, NonPositiveFocalFails) {
  auto keys = ValidYamlKeys();
  keys["camera_matrix"] = OpenCvMatrix(3, 3, "50, 0, 31.5, 0, -50, 23.5, 0, 0, 1");
  ExpectYamlError(keys, {"key 'camera_matrix' must have positive focal lengths", "fy -50"});
}

TEST_F(SequenceTest, CameraMatrixWithSkewFails) {
  auto keys = ValidYamlKeys();
  keys["camera_matrix"] = OpenCvMatrix(3, 3, "50, 0.5, 31.5, 0, 50, 23.5, 0, 0, 1");
  ExpectYamlError(keys, {"key 'camera_matrix' must have the form (fx 0 cx; 0 fy cy; 0 0 1)"});
}

TEST_F(SequenceTest, TBaseCameraWithNonRotationFails) {
  auto keys = ValidYamlKeys();
  keys["T_base_camera"] = OpenCvMatrix(4, 4, "2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1");
  ExpectYamlError(keys, {"key 'T_base_camera' rotation part is not a rotation"});
}

TEST_F(SequenceTest, TBaseCameraWithReflectionFails) {
  auto keys = ValidYamlKeys();
  keys["T_base_camera"] = OpenCvMatrix(4, 4, "-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1");
  ExpectYamlError(keys, {"key 'T_base_camera' rotation part is not a rotation", "det R = -1"});
}

TEST_F(SequenceTest, NonPositiveOdometrySigmaFails) {
  auto keys = ValidYamlKeys();
  keys["odometry_rotation_sigma"] = "-0.01";
  ExpectYamlError(keys, {"key 'odometry_rotation_sigma' must be positive"});
}

TEST_F(SequenceTest, EmptyImagesTxtFails) {
  WriteText(Path("images.txt"), "# nothing here\n\n");
  ExpectError(Read(), {Path("images.txt") + ": lists no image"});
}

TEST_F(SequenceTest, ImagesLineWithoutPathFails) {
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.1\n");
  ExpectError(Read(), {Path("images.txt") + ":2: expected '<timestamp> <relative image path>'"});
}

TEST_F(SequenceTest, ImagesLineWithBadTimestampFails) {
  WriteText(Path("images.txt"), "10.0 images/000000.png\nten images/000001.png\n");
  ExpectError(Read(), {Path("images.txt") + ":2: expected '<timestamp> <relative image path>'", "'ten "});
}

TEST_F(SequenceTest, TimestampsOutOfOrderFail) {
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.2 images/000002.png\n10.1 images/000001.png\n");
  ExpectError(Read(), {Path("images.txt") + ":3: timestamp 10.1 is not after the previous frame's 10.2"});
}

TEST_F(SequenceTest, MissingImageFileFails) {
  std::filesystem::remove(Path("images/000001.png"));
  ExpectError(Read(), {Path("images.txt") + ":4: image file " + Path("images/000001.png") + " does not exist"});
}

TEST_F(SequenceTest, ImageThatDoesNotDecodeFails) {
  WriteText(Path("images/000001.png"), "this is not a PNG");
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  ExpectError(LoadFrameImage(sequence_, 1, &grey), {Path("images/000001.png") + ": cannot decode image"});
}

TEST_F(SequenceTest, ImageOfWrongSizeFails) {
  ASSERT_TRUE(cv::imwrite(Path("images/000002.png"), cv::Mat(24, 32, CV_8UC1, cv::Scalar(7))));
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  ExpectError(LoadFrameImage(sequence_, 2, &grey),
              {Path("images/000002.png") + ": image is 32x24, sequence.yaml says 64x48"});
}

TEST_F(SequenceTest, ImageDeletedAfterReadingFails) {
  ASSERT_TRUE(Read().ok());
  std::filesystem::remove(Path("images/000000.png"));
  cv::Mat grey;
  ExpectError(LoadFrameImage(sequence_, 0, &grey), {Path("images/000000.png") + ": image file does not exist"});
}

TEST_F(SequenceTest, MissingOdometryFails) {
  std::filesystem::remove(Path("odometry.txt"));
  ExpectError(Read(), {Path("odometry.txt") + ": file does not exist"});
}

TEST_F(SequenceTest, OdometryLineWithTooFewNumbersFails) {
  WriteText(Path("odometry.txt"), "10.0 0 0 0 0 0 0 1\n10.1 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("odometry.txt") + ":2: expected 8 numbers (timestamp tx ty tz qx qy qz qw), found 7"});
}

TEST_F(SequenceTest, OdometryNanFails) {
  WriteText(Path("odometry.txt"), "10.0 0 0 0 0 0 0 1\n10.1 0 NaN 0 0 0 0 1\n");
  ExpectError(Read(), {Path("odometry.txt") + ":2: non-finite number 'NaN'"});
}

TEST_F(SequenceTest, OdometryNonUnitQuaternionFails) {
  WriteText(Path("odometry.txt"), "10.0 0 0 0 0 0 0 1\n10.1 0 0 0 0.1 0 0 1.1\n");
  ExpectError(Read(), {Path("odometry.txt") + ":2: quaternion qx qy qz qw has norm"});
}

TEST_F(SequenceTest, ImageTimestampWithNoPoseFails) {
  // 10.1 is 2 ms from its nearest odometry line: beyond the 1 ms association tolerance.
  WriteText(Path("odometry.txt"), "10.0 0 0 0 0 0 0 1\n10.098 0 0 0 0 0 0 1\n10.2 0 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("images.txt") + ":4: no pose in " + Path("odometry.txt"),
                       "within 1 ms of timestamp 10.1"});
}

TEST_F(SequenceTest, ImageTimestampWithNoGroundtruthPoseFails) {
  WriteText(Path("groundtruth.txt"), "10.0 0 0 0 0 0 0 1\n10.1 0 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("images.txt") + ":5: no pose in " + Path("groundtruth.txt")});
}

TEST_F(SequenceTest, FewerThanTwoFramesFails) {
  WriteText(Path("images.txt"), "# one frame\n10.0 images/000000.png\n");
  ExpectError(Read(), {Path("images.txt") + ": lists 1 frame, at least 2 are needed"});
}

}  // namespace
}  // namespace sfm

#include "frontend/sequence/sequence.h"

#include <glog/logging.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "geometry/tum_io.h"
#include "tests/test_data.h"
#include "util/number_text.h"

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

  // The valid sequence.yaml with `key` set to `value`.
  void ExpectYamlValueError(const std::string& key, const std::string& value,
                            const std::vector<std::string>& pieces) {
    auto keys = ValidYamlKeys();
    keys[key] = value;
    ExpectYamlError(keys, pieces);
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

// SPEC section 1 distortion_model: the written equidistant calibration reads back bit for bit;
// radtan is written without the key (as before it existed).
TEST_F(SequenceTest, EquidistantCalibrationRoundTripsWithItsModelKey) {
  Calibration written = TestCalibration();
  written.camera.model = DistortionModel::kEquidistant;
  written.camera.distortion = {0.02, -0.01, 3e-3, -4e-4, 0};
  ASSERT_TRUE(WriteCalibration(Path("sequence.yaml"), written).ok());
  Calibration read;
  const Status status = ReadCalibration(Path("sequence.yaml"), &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.camera.model, DistortionModel::kEquidistant);
  EXPECT_EQ(read.camera.distortion, written.camera.distortion);
  std::ifstream in(Path("sequence.yaml"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, HasSubstr("distortion_model: equidistant"));

  ASSERT_TRUE(WriteCalibration(Path("sequence.yaml"), TestCalibration()).ok());
  std::ifstream radtan(Path("sequence.yaml"));
  const std::string radtan_text((std::istreambuf_iterator<char>(radtan)), std::istreambuf_iterator<char>());
  EXPECT_THAT(radtan_text, Not(HasSubstr("distortion_model")));
}

TEST_F(SequenceTest, EquidistantModelReadsFourCoefficientsInEitherOrientation) {
  for (const auto& [rows, cols] : {std::pair{1, 4}, std::pair{4, 1}}) {
    auto keys = ValidYamlKeys();
    keys["distortion_model"] = "equidistant";
    keys["distortion_coefficients"] = OpenCvMatrix(rows, cols, "0.1, -0.02, 0.003, -0.0004");
    WriteText(Path("sequence.yaml"), YamlText(keys));
    Calibration calibration;
    const Status status = ReadCalibration(Path("sequence.yaml"), &calibration);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(calibration.camera.model, DistortionModel::kEquidistant);
    EXPECT_EQ(calibration.camera.distortion, (std::array<double, 5>{0.1, -0.02, 0.003, -0.0004, 0}));
  }
}

// Kalibr's radtan (k1 k2 p1 p2): k3 = 0, with or without the explicit model key.
TEST_F(SequenceTest, RadtanWithFourCoefficientsHasZeroK3) {
  for (const bool explicit_model : {false, true}) {
    auto keys = ValidYamlKeys();
    if (explicit_model) keys["distortion_model"] = "radtan";
    keys["distortion_coefficients"] = OpenCvMatrix(1, 4, "-0.28, 0.07, 2e-4, -1e-4");
    WriteText(Path("sequence.yaml"), YamlText(keys));
    Calibration calibration;
    const Status status = ReadCalibration(Path("sequence.yaml"), &calibration);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(calibration.camera.model, DistortionModel::kRadTan);
    EXPECT_EQ(calibration.camera.distortion, (std::array<double, 5>{-0.28, 0.07, 2e-4, -1e-4, 0}));
  }
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
  ExpectYamlValueError("camera_matrix", OpenCvMatrix(2, 3, "50, 0, 31.5, 0, 50, 23.5"),
                       {"key 'camera_matrix' must be 3x3, found 2x3"});
}

TEST_F(SequenceTest, CameraMatrixThatIsNotAMatrixFails) {
  ExpectYamlValueError("camera_matrix", "50", {"key 'camera_matrix' must be a 3x3 !!opencv-matrix"});
}

TEST_F(SequenceTest, MatrixDataOfWrongLengthFails) {
  ExpectYamlValueError("distortion_coefficients", OpenCvMatrix(1, 5, "-0.1, 0.01"),
                       {"key 'distortion_coefficients' is not a valid !!opencv-matrix"});
}

TEST_F(SequenceTest, UnknownDistortionModelFails) {
  ExpectYamlValueError(
      "distortion_model", "rational_polynomial",
      {"key 'distortion_model' is 'rational_polynomial', not a known model (radtan or equidistant)"});
}

TEST_F(SequenceTest, DistortionModelThatIsNotANameFails) {
  ExpectYamlValueError("distortion_model", "3", {"key 'distortion_model' must be radtan or equidistant"});
}

TEST_F(SequenceTest, EquidistantWithFiveCoefficientsFails) {
  auto keys = ValidYamlKeys();
  keys["distortion_model"] = "equidistant";
  ExpectYamlError(keys,
                  {"key 'distortion_coefficients' must be 1x4 (k1 k2 k3 k4 of distortion_model equidistant), "
                   "found 1x5"});
}

TEST_F(SequenceTest, RadtanWithThreeCoefficientsFails) {
  ExpectYamlValueError("distortion_coefficients", OpenCvMatrix(1, 3, "-0.1, 0.01, 0"),
                       {"key 'distortion_coefficients' must be 1x5 (k1 k2 p1 p2 k3) or 1x4 (k1 k2 p1 p2) for "
                        "distortion_model radtan, found 1x3"});
}

TEST_F(SequenceTest, NonIntegerImageWidthFails) {
  ExpectYamlValueError("image_width", "64.5", {"key 'image_width' must be an integer"});
}

TEST_F(SequenceTest, NonPositiveImageHeightFails) {
  ExpectYamlValueError("image_height", "0", {"key 'image_height' must be positive, found 0"});
}

TEST_F(SequenceTest, NonFiniteNumberFails) {
  ExpectYamlValueError("camera_matrix", OpenCvMatrix(3, 3, "50, 0, .nan, 0, 50, 23.5, 0, 0, 1"),
                       {"key 'camera_matrix' entry (0,2) is not finite"});
}

TEST_F(SequenceTest, NonPositiveFocalFails) {
  ExpectYamlValueError("camera_matrix", OpenCvMatrix(3, 3, "50, 0, 31.5, 0, -50, 23.5, 0, 0, 1"),
                       {"key 'camera_matrix' must have positive focal lengths", "fy -50"});
}

TEST_F(SequenceTest, CameraMatrixWithSkewFails) {
  ExpectYamlValueError("camera_matrix", OpenCvMatrix(3, 3, "50, 0.5, 31.5, 0, 50, 23.5, 0, 0, 1"),
                       {"key 'camera_matrix' must have the form (fx 0 cx; 0 fy cy; 0 0 1)"});
}

TEST_F(SequenceTest, TBaseCameraWithNonRotationFails) {
  ExpectYamlValueError("T_base_camera", OpenCvMatrix(4, 4, "2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1"),
                       {"key 'T_base_camera' rotation part is not a rotation"});
}

TEST_F(SequenceTest, TBaseCameraWithReflectionFails) {
  ExpectYamlValueError("T_base_camera", OpenCvMatrix(4, 4, "-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1"),
                       {"key 'T_base_camera' rotation part is not a rotation", "det R = -1"});
}

TEST_F(SequenceTest, NonPositiveOdometrySigmaFails) {
  ExpectYamlValueError("odometry_rotation_sigma", "-0.01",
                       {"key 'odometry_rotation_sigma' must be positive"});
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

TEST_F(SequenceTest, ImageAfterTheOdometrySpanFails) {
  // 10.2 is 50 ms after the last odometry line: nothing to interpolate from, nothing extrapolated.
  WriteText(Path("odometry.txt"), "9.95 0 0 0 0 0 0 1\n10.0 0 0 0 0 0 0 1\n10.15 0 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("images.txt") + ":5: timestamp 10.2 is outside the time span of " +
                           Path("odometry.txt") + " (9.95 to 10.15 s): 0.05 s after its last pose, more than the "
                           "1 ms tolerance"});
}

TEST_F(SequenceTest, ImageBeforeTheOdometrySpanBeyond1msFails) {
  // 1.5 ms early: just past the tolerance at the start of the span.
  WriteText(Path("odometry.txt"), "10.0015 0 0 0 0 0 0 1\n10.2 0 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("images.txt") + ":2: timestamp 10 is outside the time span of " + Path("odometry.txt") +
                       " (10.0015 to 10.2 s): 0.0015 s before its first pose"});
}

TEST_F(SequenceTest, ImageAfterTheGroundtruthSpanFails) {
  WriteText(Path("groundtruth.txt"), "10.0 0 0 0 0 0 0 1\n10.1 0 0 0 0 0 0 1\n");
  ExpectError(Read(), {Path("images.txt") + ":5: timestamp 10.2 is outside the time span of " +
                       Path("groundtruth.txt") + " (10 to 10.1 s): 0.1 s after its last pose"});
}

// --- Association of images with trajectory lines ------------------------------------------------

// Collects glog messages holding "interpolated", to check the log says so once per file.
class InterpolationLogSink : public google::LogSink {
 public:
  InterpolationLogSink() : saved_minloglevel_(FLAGS_minloglevel) {
    FLAGS_minloglevel = google::GLOG_INFO;  // the test main keeps only warnings and up
    google::AddLogSink(this);
  }
  ~InterpolationLogSink() override {
    google::RemoveLogSink(this);
    FLAGS_minloglevel = saved_minloglevel_;
  }
  void send(google::LogSeverity severity, const char*, const char*, int, const google::LogMessageTime&,
            const char* message, size_t message_len) override {
    const std::string text(message, message_len);
    if (text.find("interpolated") != std::string::npos) messages.push_back({severity, text});
  }
  std::vector<std::pair<google::LogSeverity, std::string>> messages;

 private:
  int saved_minloglevel_;
};

Pose3 RotationAboutZ(double angle, const Eigen::Vector3d& translation) {
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())), translation);
}

TEST_F(SequenceTest, ImageBetweenTwoOdometryLinesGetsTheInterpolatedPose) {
  // Lines 40 ms apart at 10.08 and 10.12: translation (1,2,3) -> (3,-2,5), rotation about z 0.2 -> 0.6
  // rad. The line at 10.12 is written with the quaternion negated (the same rotation): slerp must
  // still take the 0.4 rad arc, not the 2 pi - 0.4 one. By hand, at the midpoint 10.1 the pose is
  // (2,0,4) and 0.4 rad about z; at the quarter point 10.09 (which tells s from 1 - s) it is
  // (1.5,1,3.5) and 0.3 rad. Tolerance 1e-12 m and rad: the fraction s = (10.1 - 10.08) / 0.04 is
  // off by ~1e-15 / 0.04 from rounding of the decimal timestamps, times at most 4 m or 0.4 rad.
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.09 images/000001.png\n10.1 images/000002.png\n");
  WriteText(Path("odometry.txt"),
            "10.0 0 0 0 0 0 0 1\n"
            "10.08 1 2 3 0 0 " + ShortestNumberText(std::sin(0.1)) + " " + ShortestNumberText(std::cos(0.1)) + "\n"
            "10.12 3 -2 5 0 0 " + ShortestNumberText(-std::sin(0.3)) + " " + ShortestNumberText(-std::cos(0.3)) + "\n");
  WriteText(Path("groundtruth.txt"), "10.0 0 1 0 0 0 0 1\n10.2 0 3 0 0 0 0 1\n");
  InterpolationLogSink log;
  const Status status = Read();
  ASSERT_TRUE(status.ok()) << status.message();

  constexpr double kTolerance = 1e-12;
  const Pose3 quarter = RotationAboutZ(0.3, {1.5, 1, 3.5});
  const Pose3 midpoint = RotationAboutZ(0.4, {2, 0, 4});
  EXPECT_LT((sequence_.frames[1].world_T_base_odometry.translation - quarter.translation).norm(), kTolerance);
  EXPECT_LT(RotationAngle(sequence_.frames[1].world_T_base_odometry.rotation, quarter.rotation), kTolerance);
  EXPECT_LT((sequence_.frames[2].world_T_base_odometry.translation - midpoint.translation).norm(), kTolerance);
  EXPECT_LT(RotationAngle(sequence_.frames[2].world_T_base_odometry.rotation, midpoint.rotation), kTolerance);
  EXPECT_NEAR(sequence_.frames[2].world_T_base_odometry.rotation.norm(), 1, 1e-15);
  // The frame on a line keeps that line's pose exactly.
  EXPECT_EQ(sequence_.frames[0].world_T_base_odometry.translation, Eigen::Vector3d::Zero());
  EXPECT_EQ(sequence_.frames[0].world_T_base_odometry.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());

  // Ground truth follows the same rule between its lines at 10.0 (y = 1) and 10.2 (y = 3): 10.09 is
  // 45 % of the way (y = 1.9), 10.1 midway (y = 2).
  ASSERT_TRUE(sequence_.frames[1].world_T_base_groundtruth.has_value());
  EXPECT_NEAR(sequence_.frames[1].world_T_base_groundtruth->translation.y(), 1.9, kTolerance);
  EXPECT_NEAR(sequence_.frames[2].world_T_base_groundtruth->translation.y(), 2, kTolerance);
  EXPECT_EQ(sequence_.frames[0].world_T_base_groundtruth->translation.y(), 1);

  // Said once per file, at INFO, with the count of frames: not once per frame.
  ASSERT_EQ(log.messages.size(), 2u);
  EXPECT_EQ(log.messages[0].first, google::GLOG_INFO);
  EXPECT_THAT(log.messages[0].second, HasSubstr(Path("odometry.txt") + ": 2 of 3 images"));
  EXPECT_THAT(log.messages[0].second, HasSubstr("widest gap 0.04 s"));
  EXPECT_THAT(log.messages[1].second, HasSubstr(Path("groundtruth.txt") + ": 2 of 3 images"));
}

TEST_F(SequenceTest, HighRateOdometryIsSubsampledAtTheImageTimes) {
  // 100 Hz odometry, x = line index, rotation about z 0.01 rad per line; images at 10.0 and
  // 10.1008 (0.8 ms after line 10: within 1 ms, so that line as is, not interpolated) and 10.1045
  // (4.5 ms from the nearest line: interpolated, x = 10.45 to 1e-12).
  std::string odometry;
  for (int k = 0; k <= 20; ++k) {
    const Pose3 pose = RotationAboutZ(0.01 * k, {double(k), 0, 0});
    char timestamp[16];
    std::snprintf(timestamp, sizeof(timestamp), "%.2f", 10 + 0.01 * k);  // "10.07", as a logger writes
    odometry += std::string(timestamp) + " " + std::to_string(k) + " 0 0 0 0 " +
                ShortestNumberText(pose.rotation.z()) + " " + ShortestNumberText(pose.rotation.w()) + "\n";
  }
  WriteText(Path("odometry.txt"), odometry);
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.1008 images/000001.png\n10.1045 images/000002.png\n");
  std::filesystem::remove(Path("groundtruth.txt"));
  InterpolationLogSink log;
  const Status status = Read();
  ASSERT_TRUE(status.ok()) << status.message();
  std::vector<StampedPose> lines;
  ASSERT_TRUE(ReadTumTrajectory(Path("odometry.txt"), &lines).ok());
  ASSERT_EQ(lines.size(), 21u);

  // Lines 0 and 10 bit for bit.
  EXPECT_EQ(sequence_.frames[0].world_T_base_odometry.translation, lines[0].pose.translation);
  EXPECT_EQ(sequence_.frames[0].world_T_base_odometry.rotation.coeffs(), lines[0].pose.rotation.coeffs());
  EXPECT_EQ(sequence_.frames[1].world_T_base_odometry.translation, lines[10].pose.translation);
  EXPECT_EQ(sequence_.frames[1].world_T_base_odometry.rotation.coeffs(), lines[10].pose.rotation.coeffs());
  // 10.1045 lies between lines 10 and 11, 45 % of the way.
  const Pose3 expected = RotationAboutZ(0.1045, {10.45, 0, 0});
  EXPECT_NEAR(sequence_.frames[2].world_T_base_odometry.translation.x(), 10.45, 1e-12);
  EXPECT_LT(RotationAngle(sequence_.frames[2].world_T_base_odometry.rotation, expected.rotation), 1e-12);
  ASSERT_EQ(log.messages.size(), 1u);
  EXPECT_THAT(log.messages[0].second, HasSubstr("1 of 3 images"));
}

TEST_F(SequenceTest, ImageWithin1msOutsideTheSpanTakesTheEndLine) {
  // 0.9 ms before the first line and 0.9 ms after the last: within the tolerance, so those lines.
  WriteText(Path("odometry.txt"), "10.0009 1 0 0 0 0 0 1\n10.1 2 0 0 0 0 0 1\n10.1991 3 0 0 0 0 0 1\n");
  const Status status = Read();
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(sequence_.frames[0].world_T_base_odometry.translation.x(), 1);
  EXPECT_EQ(sequence_.frames[2].world_T_base_odometry.translation.x(), 3);
}

TEST_F(SequenceTest, FewerThanTwoFramesFails) {
  WriteText(Path("images.txt"), "# one frame\n10.0 images/000000.png\n");
  ExpectError(Read(), {Path("images.txt") + ": lists 1 frame, at least 2 are needed"});
}

// --- Input that used to be read wrong in silence or block (issue 18, items 5 and 6) ------------------

// OpenCV stores a YAML integer in an int without reporting overflow: 4294967936 read as 640 and
// 99999999999 as 1215752191. Both are refused, naming the key and the value.
TEST_F(SequenceTest, ImageSizeBeyondIntIsRefusedNotWrapped) {
  ExpectYamlValueError("image_width", "4294967936", {"key 'image_width' is 4294967936, out of range"});
  ExpectYamlValueError("image_height", "99999999999", {"key 'image_height' is 99999999999, out of range"});
  ExpectYamlValueError("image_width", "200000",
                       {"key 'image_width' is 200000, out of range (at most 100000)"});
}

// A translation of 1e300 m or a sigma of 1e300 is finite but overflows once squared; it used to be
// blamed on odometry.txt. Now sequence.yaml and the key are named.
TEST_F(SequenceTest, HugeTBaseCameraTranslationBlamesTheKey) {
  ExpectYamlValueError("T_base_camera",
                       OpenCvMatrix(4, 4, "0, 0, 1, 1e300, -1, 0, 0, 0, 0, -1, 0, 0.5, 0, 0, 0, 1"),
                       {"key 'T_base_camera' translation has a coordinate of 1e+300 m, out of range"});
}

TEST_F(SequenceTest, HugeOdometrySigmaBlamesTheKey) {
  ExpectYamlValueError("odometry_translation_sigma", "1e300",
                       {"key 'odometry_translation_sigma' is 1e+300, out of range"});
}

TEST_F(SequenceTest, TruncatedJpegIsRefusedNotDecodedWithGreyRows) {
  cv::Mat image(kHeight, kWidth, CV_8UC1);
  cv::randu(image, 0, 255);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", image, jpeg));
  WriteText(Path("images/000001.jpg"), std::string(jpeg.begin(), jpeg.end()));
  WriteText(Path("images/000002.jpg"), std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.1 images/000001.jpg\n10.2 images/000002.jpg\n");
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  EXPECT_TRUE(LoadFrameImage(sequence_, 1, &grey).ok()) << "the complete JPEG reads";
  ExpectError(LoadFrameImage(sequence_, 2, &grey),
              {Path("images/000002.jpg") + ": JPEG is truncated: no end-of-image marker"});
}

TEST_F(SequenceTest, TruncatedPngIsRefusedBeforeLibpngSeesIt) {
  const std::string png = testing::ReadFile(Path("images/000001.png"));
  WriteText(Path("images/000001.png"), png.substr(0, png.size() / 2));
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  ExpectError(LoadFrameImage(sequence_, 1, &grey), {Path("images/000001.png") + ": PNG is truncated"});
}

// A PNG that declares 30000x30000 in a few hundred kilobytes would take 900 MB to decode: its size
// is read from the IHDR chunk and refused first. The header alone is enough (the file is cut after
// it and a fake IEND, so decoding it would fail differently).
TEST_F(SequenceTest, ImageSizeIsCheckedFromTheHeaderBeforeDecoding) {
  std::string png = testing::ReadFile(Path("images/000001.png"));
  ASSERT_GT(png.size(), 24u);
  const unsigned char side[4] = {0x00, 0x00, 0x75, 0x30};  // 30000, big-endian
  png.replace(16, 4, reinterpret_cast<const char*>(side), 4);
  png.replace(20, 4, reinterpret_cast<const char*>(side), 4);
  WriteText(Path("images/000001.png"), png);
  ASSERT_TRUE(Read().ok());
  cv::Mat grey;
  ExpectError(LoadFrameImage(sequence_, 1, &grey),
              {Path("images/000001.png") + ": image is 30000x30000, sequence.yaml says 64x48"});
}

TEST_F(SequenceTest, NonRegularImagesAreNamedAsWhatTheyAre) {
  std::filesystem::remove(Path("images/000001.png"));
  std::filesystem::create_directory(Path("images/000001.png"));
  ExpectError(Read(),
              {Path("images.txt") + ":4: image file " + Path("images/000001.png") + " is a directory"});
  std::filesystem::remove(Path("images/000001.png"));
  ASSERT_EQ(mkfifo(Path("images/000001.png").c_str(), 0644), 0);
  ExpectError(Read(), {"image file " + Path("images/000001.png") + " is a FIFO (named pipe)"});
  std::filesystem::remove(Path("images/000001.png"));
  std::filesystem::create_symlink("/dev/zero", Path("images/000001.png"));
  ExpectError(Read(), {"image file " + Path("images/000001.png") + " is a character device"});
  std::filesystem::remove(Path("images/000001.png"));
  std::filesystem::create_symlink(Path("images/000001.png"), Path("images/000001.png"));
  ExpectError(Read(), {"image file " + Path("images/000001.png") + " is a symbolic link loop"});
}

// A FIFO as images.txt, odometry.txt or sequence.yaml: refused at once, never opened for a
// blocking read (the test would hang otherwise).
TEST_F(SequenceTest, FifoInputFilesAreRefusedWithoutBlocking) {
  for (const std::string name : {"images.txt", "odometry.txt", "sequence.yaml", "groundtruth.txt"}) {
    const std::string saved = testing::ReadFile(Path(name));
    std::filesystem::remove(Path(name));
    ASSERT_EQ(mkfifo(Path(name).c_str(), 0644), 0);
    ExpectError(Read(), {Path(name) + ": ", "is a FIFO (named pipe), expected a regular file"});
    std::filesystem::remove(Path(name));
    WriteText(Path(name), saved);
  }
}

TEST_F(SequenceTest, TextEncodingsAreNamed) {
  const std::string images = testing::ReadFile(Path("images.txt"));
  WriteText(Path("images.txt"), "\xEF\xBB\xBF" + images);
  ExpectError(Read(), {Path("images.txt") + ": starts with a UTF-8 byte-order mark"});
  std::string utf16 = "\xFF\xFE";
  for (const char c : images) utf16 += std::string(1, c) + '\0';
  WriteText(Path("images.txt"), utf16);
  ExpectError(Read(), {Path("images.txt") + ": is UTF-16 encoded"});
  std::string cr = images;
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  WriteText(Path("images.txt"), cr);
  ExpectError(Read(), {Path("images.txt") + ": has CR-only line endings"});
  std::string crlf;
  for (const char c : images) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  WriteText(Path("images.txt"), crlf);
  EXPECT_TRUE(Read().ok()) << "CR LF line endings are fine";
  const std::string yaml = testing::ReadFile(Path("sequence.yaml"));
  WriteText(Path("sequence.yaml"), "\xEF\xBB\xBF" + yaml);
  ExpectError(Read(), {Path("sequence.yaml") + ": starts with a UTF-8 byte-order mark"});
}

// A NUL inside an images.txt path used to cut the path there.
TEST_F(SequenceTest, NulByteInImagesTxtIsRefusedWithItsLine) {
  WriteText(Path("images.txt"),
            std::string("10.0 images/000000.png\n10.1 images/000001.png") + '\0' + ".x\n");
  ExpectError(Read(), {Path("images.txt") + ":2: holds a NUL byte"});
}

TEST_F(SequenceTest, ImagePathThatIsNotUtf8IsRefused) {
  const std::string name = "images/\xE9t\xE9.png";  // Latin-1, not UTF-8
  std::filesystem::copy_file(Path("images/000001.png"), Path(name));
  WriteText(Path("images.txt"), "10.0 images/000000.png\n10.1 " + name + "\n");
  ExpectError(Read(), {Path("images.txt") + ":2: the image path is not valid UTF-8"});
}

}  // namespace
}  // namespace sfm

#include "sequences/importers/calibration_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/test_data.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = testing::MakeScratchDir("calibration_files") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// A Kalibr camchain as kalibr_calibrate_imu_camera writes it (EuRoC MH_01's cam0 numbers).
constexpr const char* kKalibrRadtan = R"(cam0:
  T_cam_imu:
  - [0.0148655429818, 0.999557249008, -0.0257744366974, 0.0652229611843]
  - [-0.999880929698, 0.0149672133247, 0.00375618835797, -0.0207054323002]
  - [0.00414029679422, 0.0257155299480, 0.999660727178, -0.00805460246602]
  - [0.0, 0.0, 0.0, 1.0]
  camera_model: pinhole
  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
  distortion_model: radtan
  intrinsics: [458.654, 457.296, 367.215, 248.375]
  resolution: [752, 480]
  rostopic: /cam0/image_raw
)";

// Kalibr: K, the four radtan coefficients (k3 = 0), and T_base_camera = base_T_imu * T_cam_imu^-1
// to 1e-12 (the file's numbers are an orthonormal rotation to 1e-9).
TEST(CalibrationFilesTest, KalibrCamchainComposesTheBaseTransformWithTCamImu) {
  const std::string path = WriteFile("camchain.yaml", kKalibrRadtan);
  const Pose3 base_T_imu(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                         Eigen::Vector3d(0.1, 0, 0.5));
  Calibration calibration;
  CalibrationFileKind kind;
  const Status status = ReadCalibrationFile(path, base_T_imu, &calibration, &kind);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(kind, CalibrationFileKind::kKalibr);
  const Camera& camera = calibration.camera;
  EXPECT_EQ(camera.width, 752);
  EXPECT_EQ(camera.height, 480);
  EXPECT_EQ(camera.fx, 458.654);
  EXPECT_EQ(camera.cy, 248.375);
  EXPECT_EQ(camera.model, DistortionModel::kRadTan);
  EXPECT_EQ(camera.distortion, (std::array<double, 5>{-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0}));
  Eigen::Matrix4d cam_T_imu;
  cam_T_imu << 0.0148655429818, 0.999557249008, -0.0257744366974, 0.0652229611843, -0.999880929698,
      0.0149672133247, 0.00375618835797, -0.0207054323002, 0.00414029679422, 0.0257155299480, 0.999660727178,
      -0.00805460246602, 0, 0, 0, 1;
  const Eigen::Matrix4d expected = base_T_imu.Matrix4() * cam_T_imu.inverse();
  EXPECT_LT((calibration.base_T_camera.Matrix4() - expected).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(CalibrationFilesTest, KalibrEquidistantGivesTheFisheyeModel) {
  std::string text = kKalibrRadtan;
  text.replace(text.find("distortion_model: radtan"), 24, "distortion_model: equidistant");
  Calibration calibration;
  const Status status = ReadCalibrationFile(WriteFile("camchain_equi.yaml", text), Pose3(), &calibration);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(calibration.camera.model, DistortionModel::kEquidistant);
  EXPECT_EQ(calibration.camera.distortion[3], 1.76187114e-05);
}

constexpr const char* kCameraInfo = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [430.2, 0, 311.5, 0, 431.7, 242.9, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.31, 0.09, 0.0004, -0.0002, 0.01]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [430.2, 0, 311.5, 0, 0, 431.7, 242.9, 0, 0, 0, 1, 0]
)";

// camera_info has no extrinsics: T_base_camera is the given transform.
TEST(CalibrationFilesTest, RosCameraInfoPlumbBob) {
  const Pose3 base_T_camera(Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5), Eigen::Vector3d(0.2, 0, 1));
  Calibration calibration;
  CalibrationFileKind kind;
  const Status status = ReadCalibrationFile(WriteFile("camera_info.yaml", kCameraInfo), base_T_camera,
                                            &calibration, &kind);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(kind, CalibrationFileKind::kCameraInfo);
  EXPECT_EQ(calibration.camera.fy, 431.7);
  EXPECT_EQ(calibration.camera.cx, 311.5);
  EXPECT_EQ(calibration.camera.distortion, (std::array<double, 5>{-0.31, 0.09, 0.0004, -0.0002, 0.01}));
  EXPECT_EQ(calibration.base_T_camera.translation, base_T_camera.translation);
}

TEST(CalibrationFilesTest, RationalPolynomialIsRefusedWithOneLine) {
  std::string text = kCameraInfo;
  text.replace(text.find("plumb_bob"), 9, "rational_polynomial");
  Calibration calibration;
  const std::string path = WriteFile("camera_info_rational.yaml", text);
  const Status status = ReadCalibrationFile(path, Pose3(), &calibration);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(path + ": key 'distortion_model' is 'rational_polynomial', not a "
                                                 "supported model"));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
}

TEST(CalibrationFilesTest, BadFilesFailNamingTheFileAndTheProblem) {
  struct Case {
    std::string text, expected;
  };
  std::string equidistant_five = kCameraInfo;
  equidistant_five.replace(equidistant_five.find("plumb_bob"), 9, "equidistant");
  std::string omni = kKalibrRadtan;
  omni.replace(omni.find("camera_model: pinhole"), 21, "camera_model: omni");
  const Case cases[] = {
      {"cam0: [1, 2\n", ": malformed YAML"},
      {"foo: 1\n", ": not a known calibration layout"},
      {equidistant_five, "key 'distortion_model' 'equidistant' needs 4 distortion coefficients, found 5"},
      {omni, "key 'camera_model' is 'omni'; only pinhole is supported"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const std::string path = WriteFile("bad" + std::to_string(i++) + ".yaml", c.text);
    Calibration calibration;
    const Status status = ReadCalibrationFile(path, Pose3(), &calibration);
    ASSERT_FALSE(status.ok()) << c.text;
    EXPECT_THAT(status.message(), HasSubstr(path));
    EXPECT_THAT(status.message(), HasSubstr(c.expected));
    EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
  }
}

TEST(CalibrationFilesTest, PoseTextIsTumOrderOrEmpty) {
  Pose3 pose;
  ASSERT_TRUE(ParsePoseText("1 2 3 0 0 0 1", "--x", &pose).ok());
  EXPECT_EQ(pose.translation, Eigen::Vector3d(1, 2, 3));
  ASSERT_TRUE(ParsePoseText("", "--x", &pose).ok());
  EXPECT_EQ(pose.translation, Eigen::Vector3d::Zero());
  EXPECT_THAT(ParsePoseText("1 2 3", "--x", &pose).message(), HasSubstr("--x: expected 'tx ty tz qx qy qz qw'"));
  EXPECT_THAT(ParsePoseText("0 0 0 0 0 0 2", "--x", &pose).message(), HasSubstr("norm is 2"));
}

}  // namespace
}  // namespace sfm

// import_sequence --format euroc: a generated sequence written as an EuRoC / ASL folder (here, as
// the ASL layout describes it) and imported back must give the same images byte for byte, the same
// calibration, and the same odometry and true poses to 1e-9.
#include "sequences/importers/euroc_importer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "frontend/sequence/sequence.h"
#include "sequences/generator/sequence_writer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

std::int64_t Nanoseconds(double seconds) { return std::llround(seconds * 1e9); }

// "ns,x,y,z,qw,qx,qy,qz" (and EuRoC ground truth's nine more columns: velocity and biases).
std::string AslPoseLine(double timestamp, const Pose3& pose, bool groundtruth) {
  const Eigen::Quaterniond& q = pose.rotation;
  std::string line = std::to_string(Nanoseconds(timestamp));
  for (double v : {pose.translation.x(), pose.translation.y(), pose.translation.z(), q.w(), q.x(), q.y(), q.z()}) {
    line += "," + Number(v);
  }
  if (groundtruth) line += ",0,0,0,0,0,0,0,0,0";
  return line + "\n";
}

// Writes `sequence` as an ASL folder: cam0/{data.csv, data/<ns>.png, sensor.yaml} and
// state_groundtruth_estimate0/data.csv; the odometry as ASL CSV beside it (odometry.csv).
void WriteAslFolder(const Sequence& sequence, const fs::path& root) {
  fs::create_directories(root / "cam0" / "data");
  fs::create_directories(root / "state_groundtruth_estimate0");
  std::ofstream list(root / "cam0" / "data.csv"), truth(root / "state_groundtruth_estimate0" / "data.csv"),
      odometry(root / "odometry.csv");
  list << "#timestamp [ns],filename\n";
  truth << "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], "
           "v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], "
           "b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]\n";
  odometry << "#timestamp [ns],x,y,z,qw,qx,qy,qz\n";
  for (const Frame& frame : sequence.frames) {
    const std::string name = std::to_string(Nanoseconds(frame.timestamp)) + ".png";
    list << Nanoseconds(frame.timestamp) << "," << name << "\n";
    fs::copy_file(fs::path(sequence.directory) / frame.image_path, root / "cam0" / "data" / name);
    truth << AslPoseLine(frame.timestamp, *frame.world_T_base_groundtruth, true);
    odometry << AslPoseLine(frame.timestamp, frame.world_T_base_odometry, false);
  }
  const Camera& camera = sequence.calibration.camera;
  const Eigen::Matrix4d T = sequence.calibration.base_T_camera.Matrix4();
  std::string t_bs;
  for (int i = 0; i < 16; ++i) t_bs += (i ? ", " : "") + Number(T(i / 4, i % 4));
  const bool equidistant = camera.model == DistortionModel::kEquidistant;
  std::string coefficients;
  for (int i = 0; i < (equidistant ? 4 : 5); ++i) coefficients += (i ? ", " : "") + Number(camera.distortion[i]);
  std::ofstream(root / "cam0" / "sensor.yaml")
      << "sensor_type: camera\ncomment: generated\nT_BS:\n  cols: 4\n  rows: 4\n  data: [" << t_bs
      << "]\nrate_hz: 10\nresolution: [" << camera.width << ", " << camera.height
      << "]\ncamera_model: pinhole\nintrinsics: [" << Number(camera.fx) << ", " << Number(camera.fy) << ", "
      << Number(camera.cx) << ", " << Number(camera.cy) << "] #fu, fv, cu, cv\ndistortion_model: "
      << (equidistant ? "equidistant" : "radial-tangential") << "\ndistortion_coefficients: [" << coefficients
      << "]\n";
}

double PoseError(const Pose3& a, const Pose3& b) {
  return std::max((a.translation - b.translation).norm(), RotationAngle(a.rotation, b.rotation));
}

class EurocImporterTest : public ::testing::TestWithParam<DistortionModel> {};

TEST_P(EurocImporterTest, GeneratedSequenceRoundTripsThroughAnAslFolder) {
  const fs::path scratch = testing::MakeScratchDir(std::string("euroc_round_trip_") + DistortionModelName(GetParam()));
  GeneratorOptions generator;
  generator.trajectory.num_frames = 5;
  generator.camera.width = 320;
  generator.camera.height = 240;
  generator.camera.fx = generator.camera.fy = 225;
  generator.camera.model = GetParam();
  generator.camera.distortion = GetParam() == DistortionModel::kEquidistant
                                    ? std::array<double, 5>{0.02, -0.01, 0.003, -0.0004, 0}
                                    : std::array<double, 5>{-0.2, 0.05, 0.001, -0.001, 0.01};
  generator.write_truth = false;
  generator.png_compression = 1;
  ASSERT_TRUE(GenerateSequence(generator, (scratch / "generated").string(), /*overwrite=*/true).ok());
  Sequence generated;
  ASSERT_TRUE(ReadSequence((scratch / "generated").string(), &generated).ok());
  WriteAslFolder(generated, scratch / "asl");

  // Odometry as ASL CSV, and as the generated TUM file itself.
  for (const fs::path& odometry : {scratch / "asl" / "odometry.csv", scratch / "generated" / "odometry.txt"}) {
    SCOPED_TRACE(odometry.string());
    EurocImportOptions options;
    options.odometry_path = odometry.string();
    RecordedSequence recorded;
    Status status = ReadEurocSequence((scratch / "asl").string(), options, &recorded);
    ASSERT_TRUE(status.ok()) << status.message();
    status = WriteRecordedSequence(recorded, (scratch / "imported").string(), /*overwrite=*/true);
    ASSERT_TRUE(status.ok()) << status.message();
    Sequence imported;
    status = ReadSequence((scratch / "imported").string(), &imported);
    ASSERT_TRUE(status.ok()) << status.message();

    const Camera& a = generated.calibration.camera;
    const Camera& b = imported.calibration.camera;
    EXPECT_EQ(b.model, a.model);
    EXPECT_EQ(b.distortion, a.distortion);
    EXPECT_EQ(b.K(), a.K());
    EXPECT_LT(PoseError(imported.calibration.base_T_camera, generated.calibration.base_T_camera), 1e-9);
    ASSERT_EQ(imported.frames.size(), generated.frames.size());
    ASSERT_TRUE(imported.has_groundtruth);
    for (size_t i = 0; i < generated.frames.size(); ++i) {
      const Frame& g = generated.frames[i];
      const Frame& f = imported.frames[i];
      EXPECT_NEAR(f.timestamp, g.timestamp, 1e-9);
      EXPECT_EQ(testing::ReadFile((scratch / "imported" / f.image_path).string()),
                testing::ReadFile((scratch / "generated" / g.image_path).string()))
          << "frame " << i;
      EXPECT_LT(PoseError(f.world_T_base_odometry, g.world_T_base_odometry), 1e-9) << "frame " << i;
      EXPECT_LT(PoseError(*f.world_T_base_groundtruth, *g.world_T_base_groundtruth), 1e-9) << "frame " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Lens, EurocImporterTest,
                         ::testing::Values(DistortionModel::kRadTan, DistortionModel::kEquidistant));

// A 3-frame 160x120 generated sequence written as an ASL folder to scratch/asl (the generated
// sequence in scratch/generated).
void WriteSmallAslFolder(const fs::path& scratch) {
  GeneratorOptions generator;
  generator.trajectory.num_frames = 3;
  generator.camera.width = 160;
  generator.camera.height = 120;
  generator.camera.fx = generator.camera.fy = 110;
  generator.write_truth = false;
  ASSERT_TRUE(GenerateSequence(generator, (scratch / "generated").string(), /*overwrite=*/true).ok());
  Sequence generated;
  ASSERT_TRUE(ReadSequence((scratch / "generated").string(), &generated).ok());
  WriteAslFolder(generated, scratch / "asl");
}

// Odometry that ends before the last image, and no odometry at all: one line naming the file.
TEST(EurocImporterBadInputTest, OdometryThatStopsBeforeTheImagesFails) {
  const fs::path scratch = testing::MakeScratchDir("euroc_bad_odometry");
  ASSERT_NO_FATAL_FAILURE(WriteSmallAslFolder(scratch));
  const std::string odometry = (scratch / "short.txt").string();
  std::ofstream(odometry) << "0 0 0 0 0 0 0 1\n0.1 0.1 0 0 0 0 0 1\n";
  EurocImportOptions options;
  options.odometry_path = odometry;
  RecordedSequence recorded;
  Status status = ReadEurocSequence((scratch / "asl").string(), options, &recorded);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(odometry + ": the odometry ends at 0.1 s, before the image at 0.2 s"));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
  options.odometry_path.clear();
  status = ReadEurocSequence((scratch / "asl").string(), options, &recorded);
  EXPECT_THAT(status.message(), HasSubstr("holds no wheel odometry; name the robot's odometry file"));
}

// The program: --format euroc with the odometry and a Kalibr calibration imports (the camchain's
// T_cam_imu composed with --base_T_body); without --odometry, or with an odometry that stops
// early, it exits 1 with one line and leaves no output directory.
TEST(EurocImporterBadInputTest, ImportSequenceProgramImportsOrFailsWithOneLineAndNoOutput) {
  const fs::path scratch = testing::MakeScratchDir("euroc_app");
  ASSERT_NO_FATAL_FAILURE(WriteSmallAslFolder(scratch));
  std::ofstream(scratch / "camchain.yaml")
      << "cam0:\n  T_cam_imu:\n  - [1, 0, 0, 0.1]\n  - [0, 1, 0, 0]\n  - [0, 0, 1, 0]\n  - [0, 0, 0, 1]\n"
         "  camera_model: pinhole\n  distortion_coeffs: [0, 0, 0, 0]\n  distortion_model: equidistant\n"
         "  intrinsics: [110, 110, 79.5, 59.5]\n  resolution: [160, 120]\n";
  std::ofstream(scratch / "short.txt") << "0 0 0 0 0 0 0 1\n0.1 0.1 0 0 0 0 0 1\n";
  const fs::path out = scratch / "imported";
  auto run = [&](const std::string& arguments, std::string* error) {
    const std::string command = std::string(SFM_IMPORT_SEQUENCE_BINARY) + " --format euroc --input " +
                                (scratch / "asl").string() + " --output " + out.string() + " " + arguments +
                                " 2>" + (scratch / "stderr.txt").string() + " >/dev/null";
    const int status = std::system(command.c_str());
    *error = testing::ReadFile((scratch / "stderr.txt").string());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  std::string error;
  EXPECT_EQ(run("", &error), 1);
  EXPECT_THAT(error, HasSubstr("holds no wheel odometry"));
  EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << error;
  EXPECT_EQ(run("--odometry " + (scratch / "short.txt").string(), &error), 1);
  EXPECT_THAT(error, HasSubstr("the odometry ends at 0.1 s, before the image at 0.2 s"));
  EXPECT_FALSE(fs::exists(out));

  ASSERT_EQ(run("--odometry " + (scratch / "generated" / "odometry.txt").string() + " --calibration " +
                    (scratch / "camchain.yaml").string() + " --base_T_body '0 0 1 0 0 0 1'",
                &error),
            0)
      << error;
  Sequence imported;
  ASSERT_TRUE(ReadSequence(out.string(), &imported).ok());
  EXPECT_EQ(imported.calibration.camera.model, DistortionModel::kEquidistant);
  // base_T_camera = base_T_imu * T_cam_imu^-1: (0, 0, 1) + (-0.1, 0, 0).
  EXPECT_LT((imported.calibration.base_T_camera.translation - Eigen::Vector3d(-0.1, 0, 1)).norm(), 1e-12);
  EXPECT_EQ(imported.frames.size(), 3u);
}

}  // namespace
}  // namespace sfm

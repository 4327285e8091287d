// import_sequence as a user runs it: exit status, the one-line error naming the file, no output
// on bad input, and a sequence that ReadSequence accepts on good input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "frontend/sequence/sequence.h"
#include "util/number_text.h"
#include "sequences/importers/camera_odometry_noise.h"
#include "sequences/importers/imported_sequence.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct AppRun {
  int exit_status = -1;
  std::string stderr_text;
};

AppRun RunImport(const fs::path& scratch, const std::string& arguments) {
  const fs::path err = scratch / "stderr.txt";
  const std::string command = std::string(SFM_IMPORT_SEQUENCE_BINARY) + " " + arguments + " 2>" + err.string() +
                              " >/dev/null";
  const int status = std::system(command.c_str());
  AppRun run;
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  run.stderr_text = text.str();
  return run;
}

int CountLines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// The lines of stderr that are not glog's informational lines ("I<date> ..."): the error.
std::string ErrorLines(const std::string& text) {
  std::istringstream lines(text);
  std::string line, errors;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != 'I') errors += line + "\n";
  }
  return errors;
}

// A valid two-camera Strecha folder with small images, 1 m apart.
fs::path WriteStrechaFolder(const fs::path& scratch) {
  const fs::path dir = scratch / "strecha";
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "gt_dense_cameras");
  for (const char* name : {"0000.jpg", "0001.jpg"}) {
    cv::imwrite((dir / "images" / name).string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 200, 90)));
    std::ofstream(dir / "gt_dense_cameras" / (std::string(name) + ".camera"))
        << "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" << (name[3] == '0' ? "0" : "1")
        << " 0 0\n64 48\n";
  }
  return dir;
}

TEST(ImportSequenceAppTest, BadInputExitsNonZeroWithOneLineAndNoOutput) {
  const fs::path scratch = testing::MakeScratchDir("import_app_bad");
  const fs::path out = scratch / "out";
  AppRun run = RunImport(scratch, "--format strecha --input " + (scratch / "absent").string() + " --output " + out.string());
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_EQ(ErrorLines(run.stderr_text), "import_sequence: " + (scratch / "absent").string() +
                                              ": input directory does not exist\n");

  const fs::path strecha = WriteStrechaFolder(scratch);
  std::ofstream(strecha / "gt_dense_cameras" / "0001.jpg.camera")
      << "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 2\n0 0 0\n64 48\n";
  run = RunImport(scratch, "--format strecha --input " + strecha.string() + " --output " + out.string());
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_THAT(ErrorLines(run.stderr_text), HasSubstr("0001.jpg.camera: R is not a rotation"));
  EXPECT_EQ(CountLines(ErrorLines(run.stderr_text)), 1) << run.stderr_text;

  std::ofstream(strecha / "gt_dense_cameras" / "0001.jpg.camera")
      << "57.5 0 31.7\n0 57.6 20.9\n0 0 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0\n64 48\n";
  std::ofstream(strecha / "images" / "0001.jpg") << "not a JPEG";
  run = RunImport(scratch, "--format strecha --input " + strecha.string() + " --output " + out.string());
  EXPECT_EQ(run.exit_status, 1);
  // OpenCV's own diagnostics are folded into the one line.
  EXPECT_THAT(ErrorLines(run.stderr_text), HasSubstr("0001.jpg: cannot decode image"));
  EXPECT_EQ(CountLines(ErrorLines(run.stderr_text)), 1) << run.stderr_text;

  run = RunImport(scratch, "--format colmap --input " + strecha.string() + " --output " + out.string());
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_THAT(run.stderr_text, HasSubstr("--format must be vgg, strecha, tum, euroc, rosbag2 or rosbag"));
  run = RunImport(
      scratch, "--format vgg --vgg_refit=bundle --input " + strecha.string() + " --output " + out.string());
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_THAT(run.stderr_text, HasSubstr("--vgg_refit must be joint or pnp (found 'bundle')"));
  run = RunImport(scratch, "--format vgg --vgg_k1=-0.05 --vgg_k1_from_lines --input " + strecha.string() +
                               " --output " + out.string());
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_THAT(run.stderr_text, HasSubstr("--vgg_k1 and --vgg_k1_from_lines: give one"));
  EXPECT_FALSE(fs::exists(out));
}

// --vgg_refit, --vgg_k1 and --vgg_k1_from_lines through the app: import_notes.txt says which truth
// was made (with the joint refit's figures), and a given or estimated k1 reaches sequence.yaml.
TEST(ImportSequenceAppTest, VggRefitChoiceReachesTheNotesAndK1TheCamera) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  const fs::path scratch = testing::MakeScratchDir("import_app_vgg_refit");
  const std::string base = "--format vgg --input " + data + " --output ";
  AppRun run = RunImport(scratch, base + (scratch / "joint").string() + " --vgg_k1=-0.05");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  run = RunImport(scratch, base + (scratch / "pnp").string() + " --vgg_refit=pnp");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  auto text = [](const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  EXPECT_THAT(text(scratch / "joint" / "import_notes.txt"), HasSubstr("poses: joint refit"));
  EXPECT_THAT(text(scratch / "joint" / "import_notes.txt"), HasSubstr("(k1 held at -0.0500)"));
  EXPECT_THAT(text(scratch / "pnp" / "import_notes.txt"),
              HasSubstr("poses: re-estimated for the median K (PnP"));
  Sequence joint, pnp;
  ASSERT_TRUE(ReadSequence((scratch / "joint").string(), &joint).ok());
  ASSERT_TRUE(ReadSequence((scratch / "pnp").string(), &pnp).ok());
  EXPECT_EQ(joint.calibration.camera.distortion[0], -0.05);
  EXPECT_EQ(pnp.calibration.camera.distortion[0], 0);
  EXPECT_EQ(joint.calibration.camera.fx, pnp.calibration.camera.fx);  // K held at the median
  // k1 from the images' straight edges (measured -0.0612), the default; off, none.
  run = RunImport(scratch, base + (scratch / "none").string() + " --vgg_k1_from_lines=false");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  Sequence none;
  ASSERT_TRUE(ReadSequence((scratch / "none").string(), &none).ok());
  EXPECT_EQ(none.calibration.camera.distortion[0], 0);
  run = RunImport(scratch, base + (scratch / "lines").string());
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  EXPECT_THAT(text(scratch / "lines" / "import_notes.txt"), HasSubstr("k1 from the plumb-line bows of"));
  Sequence lines;
  ASSERT_TRUE(ReadSequence((scratch / "lines").string(), &lines).ok());
  EXPECT_NEAR(lines.calibration.camera.distortion[0], -0.061, 0.003);
}

TEST(ImportSequenceAppTest, ImportsAndRefusesToOverwriteUnlessAsked) {
  const fs::path scratch = testing::MakeScratchDir("import_app_good");
  const fs::path strecha = WriteStrechaFolder(scratch);
  const fs::path out = scratch / "out";
  const std::string arguments = "--format strecha --input " + strecha.string() + " --output " + out.string();
  AppRun run = RunImport(scratch, arguments + " --scale 0.5 --seed 9");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  Sequence sequence;
  const Status status = ReadSequence(out.string(), &sequence);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(sequence.calibration.camera.width, 32);
  EXPECT_DOUBLE_EQ(sequence.calibration.camera.cx, 0.5 * (31.7 + 0.5) - 0.5);

  run = RunImport(scratch, arguments);
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_THAT(run.stderr_text, HasSubstr("exists and is not empty"));
  run = RunImport(scratch, arguments + " --overwrite");
  EXPECT_EQ(run.exit_status, 0) << run.stderr_text;
  ASSERT_TRUE(ReadSequence(out.string(), &sequence).ok());
  EXPECT_EQ(sequence.calibration.camera.width, 64);
  for (const fs::directory_entry& entry : fs::directory_iterator(scratch)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "out" || name == "strecha" || name == "stderr.txt") << "left behind: " << name;
  }
}

// --odometry_noise_scale 3 writes what the four noise flags at three times their defaults write:
// the same odometry.txt and sequence.yaml, byte for byte (the tripled values passed as their shortest
// text, so both runs hold the same doubles); its sigmas in sequence.yaml are 3x the default run's
// (1e-15); a negative scale is a bad flag (exit 2, one line).
TEST(ImportSequenceAppTest, OdometryNoiseScaleMultipliesEveryNoiseTerm) {
  const fs::path scratch = testing::MakeScratchDir("import_app_noise_scale");
  const fs::path strecha = WriteStrechaFolder(scratch);
  const std::string base = "--format strecha --seed 5 --input " + strecha.string() + " --output ";
  AppRun run = RunImport(scratch, base + (scratch / "scaled").string() + " --odometry_noise_scale 3");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  const CameraOdometryNoiseOptions tripled = CameraOdometryNoiseOptions().Scaled(3);
  run = RunImport(scratch, base + (scratch / "flags").string() + " --odometry_scale_error " +
                               ShortestNumberText(tripled.scale_error) + " --odometry_distance_sigma " +
                               ShortestNumberText(tripled.distance_sigma) + " --odometry_rotation_sigma " +
                               ShortestNumberText(tripled.rotation_sigma) + " --odometry_heading_bias " +
                               ShortestNumberText(tripled.rotation_bias));
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  run = RunImport(scratch, base + (scratch / "default").string());
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  const auto read = [](const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  for (const char* file : {"odometry.txt", "sequence.yaml"}) {
    EXPECT_EQ(read(scratch / "scaled" / file), read(scratch / "flags" / file)) << file;
  }
  EXPECT_NE(read(scratch / "scaled" / "odometry.txt"), read(scratch / "default" / "odometry.txt"));
  Sequence scaled, plain;
  ASSERT_TRUE(ReadSequence((scratch / "scaled").string(), &scaled).ok());
  ASSERT_TRUE(ReadSequence((scratch / "default").string(), &plain).ok());
  EXPECT_NEAR(scaled.calibration.odometry_noise.translation_sigma,
              3 * plain.calibration.odometry_noise.translation_sigma, 1e-15);
  EXPECT_NEAR(scaled.calibration.odometry_noise.rotation_sigma,
              3 * plain.calibration.odometry_noise.rotation_sigma, 1e-15);

  run = RunImport(scratch, base + (scratch / "negative").string() + " --odometry_noise_scale=-1");
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_EQ(CountLines(ErrorLines(run.stderr_text)), 1) << run.stderr_text;
  EXPECT_THAT(run.stderr_text, HasSubstr("--odometry_noise_scale"));
  EXPECT_FALSE(fs::exists(scratch / "negative"));
}

// image_warps.txt through the library's reader (failing the test on a read error).
std::vector<Eigen::Matrix<double, 2, 3>> WarpsOf(const fs::path& path) {
  std::vector<Eigen::Matrix<double, 2, 3>> warps;
  const Status read = ReadImageWarps(path.string(), &warps);
  EXPECT_TRUE(read.ok()) << read.message();
  return warps;
}

// The reader names the file and the line of a malformed row (here five numbers) and of a NaN.
TEST(ImportSequenceAppTest, ImageWarpsReaderNamesTheBadLine) {
  const fs::path scratch = testing::MakeScratchDir("image_warps_reader");
  const fs::path path = scratch / "image_warps.txt";
  std::vector<Eigen::Matrix<double, 2, 3>> warps;
  {
    std::ofstream out(path);
    out << "# header\nimages/000000.png 1 0 0 0 1 0\nimages/000001.png 1 0 0 0 1\n";
  }
  Status read = ReadImageWarps(path.string(), &warps);
  ASSERT_FALSE(read.ok());
  EXPECT_THAT(read.message(), ::testing::HasSubstr(path.string() + ": line 3"));
  {
    std::ofstream out(path);
    out << "images/000000.png 1 0 nan 0 1 0\n";
  }
  read = ReadImageWarps(path.string(), &warps);
  ASSERT_FALSE(read.ok());
  EXPECT_THAT(read.message(), ::testing::HasSubstr(": line 1"));
  {
    std::ofstream out(path);
    out << "images/000000.png 2 0 1 0 2 -1\n";
  }
  ASSERT_TRUE(ReadImageWarps(path.string(), &warps).ok());
  ASSERT_EQ(warps.size(), 1u);
  EXPECT_EQ(warps[0](0, 2), 1);
  EXPECT_FALSE(ReadImageWarps((scratch / "absent.txt").string(), &warps).ok());
}

// --vgg_warp_to_shared_k through the app, with --scale: image_warps.txt must map the data set's
// pixels to the written (scaled) image's, i.e. the warp followed by the pixel-centre scaling
// x' = s (x + 0.5) - 0.5 of sequence.yaml's K (to 1e-9 px); without the flag no such file.
TEST(ImportSequenceAppTest, VggWarpFileComposesTheScaling) {
  const std::string data = testing::SharedDataDir("vgg-corridor");
  if (data.empty()) GTEST_SKIP() << "../shared/data/vgg-corridor is absent";
  const fs::path scratch = testing::MakeScratchDir("import_app_vgg_warp");
  const std::string base = "--format vgg --input " + data + " --vgg_warp_to_shared_k --output ";
  AppRun run = RunImport(scratch, base + (scratch / "full").string());
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  run = RunImport(scratch, base + (scratch / "half").string() + " --scale 0.5");
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  Sequence full, half;
  ASSERT_TRUE(ReadSequence((scratch / "full").string(), &full).ok());
  ASSERT_TRUE(ReadSequence((scratch / "half").string(), &half).ok());
  const std::vector<Eigen::Matrix<double, 2, 3>> full_warps = WarpsOf(scratch / "full" / "image_warps.txt");
  const std::vector<Eigen::Matrix<double, 2, 3>> half_warps = WarpsOf(scratch / "half" / "image_warps.txt");
  ASSERT_EQ(full_warps.size(), 11u);
  ASSERT_EQ(half_warps.size(), 11u);
  const Camera& a = full.calibration.camera;
  const Camera& b = half.calibration.camera;
  const double sx = static_cast<double>(b.width) / a.width, sy = static_cast<double>(b.height) / a.height;
  EXPECT_NEAR(b.cx, sx * (a.cx + 0.5) - 0.5, 1e-9);
  for (size_t i = 0; i < 11; ++i) {
    for (const Eigen::Vector3d& source :
         {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(511, 17, 1), Eigen::Vector3d(100, 400, 1)}) {
      const Eigen::Vector2d x = full_warps[i] * source;
      const Eigen::Vector2d expected(sx * (x.x() + 0.5) - 0.5, sy * (x.y() + 0.5) - 0.5);
      EXPECT_LT((half_warps[i] * source - expected).norm(), 1e-9) << "image " << i;
    }
  }
  run = RunImport(scratch, "--format vgg --input " + data + " --output " + (scratch / "plain").string());
  ASSERT_EQ(run.exit_status, 0) << run.stderr_text;
  EXPECT_FALSE(fs::exists(scratch / "plain" / "image_warps.txt"));
}

}  // namespace
}  // namespace sfm

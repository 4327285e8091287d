// junction_sfm as a user runs it: exit status, the one-line error on bad input, and no output
// written when the input is bad (SPEC section 2).
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

// `prefix`: shell words before the program (e.g. "ulimit -v 400000;"). `quiet`: --minloglevel=2.
RunResult RunJunctionSfm(const std::string& arguments, const fs::path& scratch, bool quiet = true,
                         const std::string& prefix = "") {
  const std::string binary = SFM_JUNCTION_SFM_BINARY;
  const fs::path err = scratch / "stderr.txt";
  const std::string command = prefix + binary + " --progress=false " + (quiet ? "--minloglevel=2 " : "") +
                              arguments + " > /dev/null 2> " + err.string();
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

  // The same, for an output directory that exists and must be left as it is.
  void ExpectOneLineErrorKeepingOutput(const std::vector<std::string>& fragments) {
    const RunResult result =
        RunJunctionSfm("--sequence=" + sequence_.string() + " --output=" + output_.string(), scratch_);
    EXPECT_NE(result.exit_code, 0);
    EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1)
        << result.stderr_text;
    for (const std::string& fragment : fragments) EXPECT_THAT(result.stderr_text, HasSubstr(fragment));
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
// coordinates); it must be refused in one line, not abort in the matcher's CHECK (exit 134).
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

// --- The output directory as one unit and one-line errors (issue 18) ----------------------------

// Everything in `dir`'s parent: the output and nothing beside it (no staging directory, no lock).
std::vector<std::string> Beside(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir.parent_path()))
    names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

// Item 1: a name with a space passed validation and the COLMAP export refused it after 20 of 25
// files were written. Now it is refused before any work, naming images.txt.
TEST_F(JunctionSfmBadInput, ImagePathWithWhiteSpaceIsRefusedBeforeTheWork) {
  fs::rename(sequence_ / "images" / "000001.png", sequence_ / "images" / "000 001.png");
  WriteText(sequence_ / "images.txt",
            "0.0 images/000000.png\n0.1 images/000 001.png\n0.2 images/000002.png\n");
  ExpectOneLineError({(sequence_ / "images.txt").string(), "frame 1", "white space", "colmap/images.txt"});
  EXPECT_FALSE(fs::exists(output_));
}

// Item 1: a run that fails leaves the earlier output byte for byte and nothing beside it (an image
// name with a space used to fail in the COLMAP export after 20 of 25 files had been rewritten);
// a run that fails where there was no output leaves no directory.
TEST_F(JunctionSfmBadInput, AFailedRunLeavesTheEarlierOutputAsItWas) {
  const std::string io = "--sequence=" + sequence_.string() + " --output=" + output_.string();
  ASSERT_EQ(RunJunctionSfm(io, scratch_).exit_code, 0);
  const auto before = testing::ReadTree(output_.string());
  fs::rename(sequence_ / "images" / "000001.png", sequence_ / "images" / "000 001.png");
  WriteText(sequence_ / "images.txt",
            "0.0 images/000000.png\n0.1 images/000 001.png\n0.2 images/000002.png\n");
  EXPECT_NE(RunJunctionSfm(io, scratch_).exit_code, 0);
  EXPECT_EQ(testing::ReadTree(output_.string()), before);
  EXPECT_EQ(Beside(output_), (std::vector<std::string>{"output", "sequence", "stderr.txt"}));
  fs::remove_all(output_);
  EXPECT_NE(RunJunctionSfm(io, scratch_).exit_code, 0);
  EXPECT_EQ(Beside(output_), (std::vector<std::string>{"sequence", "stderr.txt"}));
}

// Item 2: runs never mix. A stale junction file of a longer run and a ground-truth trajectory of a
// run with ground truth are gone after a run that writes neither.
TEST_F(JunctionSfmBadInput, ASuccessfulRunReplacesTheEarlierOutputWhole) {
  const std::string io = "--sequence=" + sequence_.string() + " --output=" + output_.string();
  ASSERT_EQ(RunJunctionSfm(io, scratch_).exit_code, 0);
  ASSERT_TRUE(fs::exists(output_ / "trajectory_groundtruth.txt"));
  WriteText(output_ / "junctions" / "000039.json", "{}");
  fs::remove(sequence_ / "groundtruth.txt");
  const RunResult result = RunJunctionSfm(io, scratch_);
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  EXPECT_FALSE(fs::exists(output_ / "junctions" / "000039.json"));
  EXPECT_FALSE(fs::exists(output_ / "trajectory_groundtruth.txt"));
  EXPECT_TRUE(fs::exists(output_ / "metrics.json"));
  EXPECT_EQ(Beside(output_), (std::vector<std::string>{"output", "sequence", "stderr.txt"}));
}

TEST_F(JunctionSfmBadInput, ADirectoryThatIsNotAnEarlierOutputIsNotReplaced) {
  fs::create_directories(output_);
  WriteText(output_ / "notes.txt", "mine");
  ExpectOneLineErrorKeepingOutput({output_.string(), "holds 'notes.txt'"});
  EXPECT_EQ(testing::ReadFile(output_ / "notes.txt"), "mine");
}

// SPEC section 2: a second run into the same output directory is refused with one line. The first
// run is played by this test holding the lock.
TEST_F(JunctionSfmBadInput, ASecondRunIntoTheSameDirectoryIsRefused) {
  const int fd = open((scratch_ / ".output.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  ExpectOneLineError({output_.string(), "another junction_sfm run", "is writing this output directory"});
  close(fd);
}

// Item 7: with glog's default levels, the error is the only line on stderr (the INFO lines go to
// junction_sfm.log); a successful run prints one summary line naming the output directory.
TEST_F(JunctionSfmBadInput, StderrHoldsOnlyTheErrorOrTheSummary) {
  const std::string io = "--sequence=" + sequence_.string() + " --output=" + output_.string();
  const RunResult ok = RunJunctionSfm(io, scratch_, /*quiet=*/false);
  ASSERT_EQ(ok.exit_code, 0) << ok.stderr_text;
  // Warnings may come first (this sequence's images give no pair a pose, and the run says so);
  // the last line is the summary.
  std::istringstream lines(ok.stderr_text);
  std::vector<std::string> stderr_lines;
  for (std::string line; std::getline(lines, line);) stderr_lines.push_back(line);
  ASSERT_FALSE(stderr_lines.empty());
  for (size_t i = 0; i + 1 < stderr_lines.size(); ++i) EXPECT_EQ(stderr_lines[i][0], 'W') << stderr_lines[i];
  EXPECT_THAT(stderr_lines.back(), HasSubstr("3 frames"));
  EXPECT_THAT(ok.stderr_text, HasSubstr("outputs in " + output_.string()));
  EXPECT_THAT(ReadFile(output_ / "junction_sfm.log"), HasSubstr("sequence " + sequence_.string()));

  cv::imwrite((sequence_ / "images" / "000002.png").string(), cv::Mat(10, 10, CV_8UC1, cv::Scalar(1)));
  const RunResult bad = RunJunctionSfm(io, scratch_, /*quiet=*/false);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(std::count(bad.stderr_text.begin(), bad.stderr_text.end(), '\n'), 1) << bad.stderr_text;
  EXPECT_THAT(bad.stderr_text, HasSubstr("junction_sfm: " + (sequence_ / "images" / "000002.png").string()));
}

// Item 7: flag errors name the flag a user typed, in one line; --threads=100000 is refused, not
// 287 warnings.
TEST_F(JunctionSfmBadInput, FlagErrorsNameTheFlag) {
  const std::string io = "--sequence=" + sequence_.string() + " --output=" + output_.string();
  const RunResult threads = RunJunctionSfm(io + " --threads=100000", scratch_, /*quiet=*/false);
  EXPECT_EQ(threads.exit_code, 2);
  EXPECT_EQ(threads.stderr_text, "junction_sfm: --threads=100000: must be between 1 and 256\n");
  const RunResult zero = RunJunctionSfm(io + " --threads=0", scratch_, /*quiet=*/false);
  EXPECT_EQ(zero.stderr_text, "junction_sfm: --threads=0: must be between 1 and 256\n");
  const RunResult loss = RunJunctionSfm(io + " --ba_loss_scale=-1", scratch_, /*quiet=*/false);
  EXPECT_EQ(loss.exit_code, 2);
  EXPECT_EQ(loss.stderr_text, "junction_sfm: --ba_loss_scale=-1: must be > 0 px\n");
  const RunResult gate = RunJunctionSfm(io + " --extend_tracks_max_gate_px=0", scratch_, /*quiet=*/false);
  EXPECT_THAT(gate.stderr_text, HasSubstr("junction_sfm: --extend_tracks_max_gate_px=0: must be"));
  EXPECT_FALSE(fs::exists(output_));
}

// Item 4: memory exhaustion was an uncaught std::bad_alloc / cv::Exception (exit 134, a core, 15
// files written). Under a 600 MB address-space limit, frames of 8000x6000 cannot be held: one
// line, exit 1, nothing written.
TEST_F(JunctionSfmBadInput, OutOfMemoryIsOneLineAndWritesNothing) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space, so ulimit -v cannot limit the run";
#endif
  WriteText(sequence_ / "sequence.yaml",
            "%YAML:1.0\n---\nimage_width: 8000\nimage_height: 6000\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
            "   data: [ 6000., 0., 4000., 0., 6000., 3000., 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
            "   data: [ 0., 0., 0., 0., 0. ]\n"
            "T_base_camera: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
            "   data: [ 0., 0., 1., 0., -1., 0., 0., 0., 0., -1., 0., 1., 0., 0., 0., 1. ]\n");
  for (int i = 0; i < 3; ++i) {
    cv::Mat image(6000, 8000, CV_8UC1, cv::Scalar(40));
    cv::rectangle(image, cv::Rect(1000 + 300 * i, 1000, 3000, 2500), cv::Scalar(200), -1);
    cv::imwrite((sequence_ / "images" / ("00000" + std::to_string(i) + ".png")).string(), image);
  }
  const RunResult result =
      RunJunctionSfm("--sequence=" + sequence_.string() + " --output=" + output_.string(), scratch_,
                     /*quiet=*/false, "ulimit -v 600000; ");
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;
  EXPECT_EQ(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n'), 1) << result.stderr_text;
  EXPECT_THAT(result.stderr_text, HasSubstr("out of memory"));
  EXPECT_FALSE(fs::exists(output_));
  EXPECT_EQ(Beside(output_), (std::vector<std::string>{"sequence", "stderr.txt"}));
}

// What `program` (in build/bin) prints on stdout with `arguments`, checking its exit status
// (junction_sfm --help: 0; gflags' own listings, --helpfull and --helpxml, exit 1).
std::string ProgramStdout(const std::string& program, const std::string& arguments, int expected_exit) {
  const std::string command = std::string(SFM_BIN_DIR) + "/" + program + " " + arguments + " 2>/dev/null";
  std::string text;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) text.append(buffer, n);
  const int status = pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == expected_exit) << command;
  return text;
}

std::string JunctionSfmStdout(const std::string& arguments, int expected_exit = 0) {
  return ProgramStdout("junction_sfm", arguments, expected_exit);
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

// Item 8: --help was 346 lines, glog's and gflags' flags first and the program's grouped under
// build paths. Now: under 80 lines, the three flags a first run needs in the first 30, no build
// path, and every flag the program defines (the sfm_app files of --helpxml) listed, so a new flag
// cannot be left out of the help table.
TEST(JunctionSfmHelp, ShortGroupedAndComplete) {
  const std::vector<std::string> help = Lines(JunctionSfmStdout("--help"));
  EXPECT_LT(help.size(), 80u);
  for (const std::string flag : {"--sequence=", "--output=", "--threads="}) {
    const auto line = std::find_if(help.begin(), help.end(),
                                   [&](const std::string& l) { return l.rfind("  " + flag, 0) == 0; });
    ASSERT_NE(line, help.end()) << flag;
    EXPECT_LT(line - help.begin(), 30) << flag;
  }
  const std::string text = JunctionSfmStdout("--help");
  EXPECT_THAT(text, ::testing::Not(HasSubstr("Flags from")));
  EXPECT_THAT(text, ::testing::Not(HasSubstr(".cc")));
  // A readable default: 6 significant digits, not gflags' 17.
  EXPECT_FALSE(std::regex_search(text, std::regex("=[0-9.]*[0-9]{9}")));

  const std::string xml = JunctionSfmStdout("--helpxml", 1);
  const std::regex flag_in_file("<file>([^<]*)</file><name>([^<]*)</name>");
  std::set<std::string> program_flags;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), flag_in_file); it != std::sregex_iterator();
       ++it) {
    if ((*it)[1].str().find("sfm_app/") != std::string::npos) program_flags.insert((*it)[2].str());
  }
  // The program's own flags: at least 30 (else --helpxml no longer names the program's files), at
  // most 35 (user choices and the paper's parameters; research switches are not flags).
  EXPECT_GE(program_flags.size(), 30u) << "--helpxml no longer names the program's files";
  EXPECT_LE(program_flags.size(), 35u) << "junction_sfm has more than 35 flags of its own";
  for (const std::string& flag : program_flags) {
    EXPECT_THAT(text, HasSubstr("\n  --" + flag + "=")) << "--" << flag << " is missing from the help table";
  }
  // Only the program's flags: glog's are left to --helpfull.
  EXPECT_THAT(text, ::testing::Not(HasSubstr("--stderrthreshold")));
}

// Item 8: one concept, one flag name in every program. detect_junctions named the end-point model
// and the junction threshold --lambda, --mu, --min_probability; match_junctions's picture was
// --image / --image_scale (detect_junctions's --image is its input); import_sequence's heading drift
// was --odometry_rotation_bias (junction_sfm's flag of that name switches the estimate of a bias).
TEST(JunctionSfmHelp, OneConceptOneFlagNameInEveryProgram) {
  const std::map<std::string, std::vector<std::string>> kNames = {
      {"junction_sfm", {"endpoint_lambda", "endpoint_mu", "junction_min_probability", "sequence", "output"}},
      {"detect_junctions",
       {"endpoint_lambda", "endpoint_mu", "junction_min_probability", "overlay", "overlay_scale"}},
      {"match_junctions",
       {"endpoint_lambda", "endpoint_mu", "junction_min_probability", "sequence", "overlay",
        "overlay_scale"}},
      {"import_sequence", {"output", "seed", "overwrite", "odometry_scale_error", "odometry_heading_bias"}},
      {"make_sequence", {"output", "seed", "overwrite", "odometry_scale_error", "odometry_heading_bias"}},
  };
  const std::vector<std::string> kRetired = {"lambda", "mu", "min_probability", "image_scale"};
  for (const auto& [program, names] : kNames) {
    const std::string xml = ProgramStdout(program, "--helpxml", 1);
    for (const std::string& name : names) {
      EXPECT_THAT(xml, HasSubstr("<name>" + name + "</name>")) << program << " lacks --" << name;
    }
    for (const std::string& name : kRetired) {
      EXPECT_THAT(xml, ::testing::Not(HasSubstr("<name>" + name + "</name>")))
          << program << " has --" << name;
    }
  }
  EXPECT_THAT(ProgramStdout("import_sequence", "--helpxml", 1),
              ::testing::Not(HasSubstr("<name>odometry_rotation_bias</name>")));
  EXPECT_THAT(ProgramStdout("match_junctions", "--helpxml", 1),
              ::testing::Not(HasSubstr("<name>image</name>")));
}

// --helpfull keeps gflags' full listing, glog's flags included.
TEST(JunctionSfmHelp, HelpfullKeepsEveryFlag) {
  const std::string full = JunctionSfmStdout("--helpfull", 1);
  EXPECT_THAT(full, HasSubstr("-stderrthreshold"));
  EXPECT_THAT(full, HasSubstr("-wireframe_far_end_along_px"));
  EXPECT_GT(Lines(full).size(), 80u);
}

}  // namespace
}  // namespace sfm

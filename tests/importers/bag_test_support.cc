#include "tests/importers/bag_test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "tests/test_data.h"

namespace sfm::testing {

AppRun RunProgram(const std::string& binary, const std::string& arguments, const std::string& scratch) {
  const std::string err = scratch + "/stderr.txt";
  const std::string command = binary + " " + arguments + " 2>" + err + " >/dev/null";
  const int status = std::system(command.c_str());
  AppRun run;
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::istringstream lines(ReadFile(err));
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != 'I') run.errors += line + "\n";
  }
  return run;
}

void ExpectSameSequence(const Sequence& original, const std::string& imported_dir, bool colour) {
  Sequence imported;
  const Status status = ReadSequence(imported_dir, &imported);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(imported.frames.size(), original.frames.size());
  ASSERT_TRUE(imported.has_groundtruth);
  const Calibration& a = original.calibration;
  const Calibration& b = imported.calibration;
  EXPECT_EQ(b.camera.K(), a.camera.K());
  EXPECT_EQ(b.camera.distortion, a.camera.distortion);
  EXPECT_LT((b.base_T_camera.Matrix4() - a.base_T_camera.Matrix4()).cwiseAbs().maxCoeff(), 1e-9);
  for (size_t i = 0; i < imported.frames.size(); ++i) {
    const Frame& x = original.frames[i];
    const Frame& y = imported.frames[i];
    EXPECT_NEAR(y.timestamp, x.timestamp, 1e-9);
    EXPECT_LT((y.world_T_base_odometry.translation - x.world_T_base_odometry.translation).norm(), 1e-9);
    EXPECT_LT(RotationAngle(y.world_T_base_odometry.rotation, x.world_T_base_odometry.rotation), 1e-9);
    EXPECT_LT((y.world_T_base_groundtruth->translation - x.world_T_base_groundtruth->translation).norm(),
              1e-9);
    EXPECT_LT(RotationAngle(y.world_T_base_groundtruth->rotation, x.world_T_base_groundtruth->rotation),
              1e-9);
    cv::Mat image = cv::imread(original.directory + "/" + x.image_path, cv::IMREAD_UNCHANGED);
    const cv::Mat read = cv::imread(imported_dir + "/" + y.image_path, cv::IMREAD_UNCHANGED);
    if (colour) cv::cvtColor(cv::Mat(image), image, cv::COLOR_GRAY2BGR);
    ASSERT_EQ(read.type(), image.type()) << i;
    ASSERT_EQ(read.size(), image.size()) << i;
    EXPECT_EQ(cv::norm(read, image, cv::NORM_INF), 0) << "frame " << i;
  }
}

}  // namespace sfm::testing

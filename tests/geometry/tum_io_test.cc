#include "geometry/tum_io.h"

#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_data.h"

namespace sfm {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string WriteText(const std::string& test_name, const std::string& text) {
  const std::string path = testing::MakeScratchDir(test_name) + "/odometry.txt";
  std::ofstream(path) << text;
  return path;
}

TEST(TumIoTest, WriteThenReadRoundTripIsBitExact) {
  std::vector<StampedPose> poses;
  for (int i = 0; i < 50; ++i) {
    StampedPose p;
    p.timestamp = 1.6e9 + i / 30.0;
    p.pose = Pose3(Eigen::Quaterniond::UnitRandom(), Eigen::Vector3d::Random() * 1e3);
    poses.push_back(p);
  }
  const std::string path = testing::MakeScratchDir("tum_round_trip") + "/trajectory.txt";
  ASSERT_TRUE(WriteTumTrajectory(path, poses).ok());
  std::vector<StampedPose> read;
  const Status status = ReadTumTrajectory(path, &read);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(read.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].timestamp, poses[i].timestamp);
    EXPECT_EQ(read[i].pose.translation, poses[i].pose.translation);
    EXPECT_EQ(read[i].pose.rotation.coeffs(), poses[i].pose.rotation.coeffs());
  }
}

TEST(TumIoTest, FormatStartsWithAHeaderCommentAndWritesQxQyQzQw) {
  StampedPose p;
  p.timestamp = 2.5;
  p.pose = Pose3(Eigen::Quaterniond(0, 1, 0, 0), Eigen::Vector3d(1, 2, 3));  // w x y z
  EXPECT_EQ(FormatTumTrajectory({p}), "# timestamp tx ty tz qx qy qz qw\n2.5 1 2 3 1 0 0 0\n");
}

TEST(TumIoTest, ReadsCommentsBlankLinesAndNormalisesANearlyUnitQuaternion) {
  const std::string path = WriteText("tum_comments", "# header\n\n1.0 0 0 0 0 0 0 1.0005  # trailing\n\n2.0 1 0 0 0 0 0 1\n");
  std::vector<StampedPose> poses;
  const Status status = ReadTumTrajectory(path, &poses);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_NEAR(poses[0].pose.rotation.norm(), 1.0, 1e-15);
  EXPECT_EQ(poses[1].pose.translation.x(), 1.0);
}

struct BadTum {
  const char* name;
  const char* text;
  const char* problem;
};

class TumIoBadInputTest : public ::testing::TestWithParam<BadTum> {};

TEST_P(TumIoBadInputTest, FailsWithOneLineNamingFileLineAndProblem) {
  const std::string path = WriteText(std::string("tum_bad_") + GetParam().name, GetParam().text);
  std::vector<StampedPose> poses;
  const Status status = ReadTumTrajectory(path, &poses);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(path));
  EXPECT_THAT(status.message(), HasSubstr(GetParam().problem));
  EXPECT_THAT(status.message(), Not(HasSubstr("\n")));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, TumIoBadInputTest,
    ::testing::Values(
        BadTum{"too_few", "# c\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n",
               ":3: expected 8 numbers (timestamp tx ty tz qx qy qz qw), found 7"},
        BadTum{"too_many", "1 0 0 0 0 0 0 1 9\n", ":1: expected 8 numbers"},
        BadTum{"not_a_number", "1 0 0 x 0 0 0 1\n", ":1: 'x' is not a number"},
        BadTum{"nan", "1 0 0 nan 0 0 0 1\n", ":1: non-finite number 'nan'"},
        BadTum{"inf", "1 0 0 0 0 0 0 inf\n", ":1: non-finite number 'inf'"},
        BadTum{"non_unit_quaternion", "1 0 0 0 0 0 0 0.5\n", ":1: quaternion qx qy qz qw has norm 0.5"},
        BadTum{"timestamps_repeat", "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", ":2: timestamp 1 does not increase"},
        BadTum{"empty", "# only a comment\n\n", ": no pose"}),
    [](const ::testing::TestParamInfo<BadTum>& info) { return std::string(info.param.name); });

TEST(TumIoTest, MissingFileFailsNamingIt) {
  std::vector<StampedPose> poses;
  const std::string path = testing::MakeScratchDir("tum_missing") + "/absent.txt";
  const Status status = ReadTumTrajectory(path, &poses);
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(path + ": file does not exist"));
}

}  // namespace
}  // namespace sfm

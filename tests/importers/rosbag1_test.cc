// ROS 1 bags: import_sequence --format rosbag on bags that the ROS library itself (rosbag_storage)
// writes from a generated sequence, uncompressed, LZ4 and BZ2; and a corrupt bag.
#include <geometry_msgs/PoseStamped.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "frontend/sequence/sequence.h"
#include "tests/importers/bag_test_support.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

ros::Time Stamp(std::int64_t nanoseconds) {
  return ros::Time(static_cast<std::uint32_t>(nanoseconds / 1000000000),
                   static_cast<std::uint32_t>(nanoseconds % 1000000000));
}

void SetPose(const Pose3& pose, geometry_msgs::Point* t, geometry_msgs::Quaternion* q) {
  t->x = pose.translation.x(), t->y = pose.translation.y(), t->z = pose.translation.z();
  q->x = pose.rotation.x(), q->y = pose.rotation.y(), q->z = pose.rotation.z(), q->w = pose.rotation.w();
}

geometry_msgs::TransformStamped Transform(const std::string& parent, const std::string& child,
                                          const Pose3& pose) {
  geometry_msgs::TransformStamped transform;
  transform.header.frame_id = parent;
  transform.child_frame_id = child;
  transform.transform.translation.x = pose.translation.x();
  transform.transform.translation.y = pose.translation.y();
  transform.transform.translation.z = pose.translation.z();
  transform.transform.rotation.x = pose.rotation.x();
  transform.transform.rotation.y = pose.rotation.y();
  transform.transform.rotation.z = pose.rotation.z();
  transform.transform.rotation.w = pose.rotation.w();
  return transform;
}

// The sequence as a ROS 1 bag written by rosbag::Bag: images (`encoding` mono8, rgb8, or png as
// CompressedImage), camera_info, /odom (Odometry), /groundtruth (PoseStamped), /tf_static.
void WriteRos1Bag(const Sequence& sequence, const std::string& path, const std::string& encoding,
                  rosbag::compression::CompressionType compression) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(compression);
  const Pose3 base_T_link(Eigen::Quaterniond(Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitZ())),
                          Eigen::Vector3d(0.2, 0.05, 0.3));
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(Transform("base_link", "camera_link", base_T_link));
  tf.transforms.push_back(
      Transform("camera_link", "camera_optical", base_T_link.Inverse() * sequence.calibration.base_T_camera));
  bag.write("/tf_static", ros::Time(1), tf);
  const Camera& camera = sequence.calibration.camera;
  for (const Frame& frame : sequence.frames) {
    const std::int64_t stamp = std::llround(frame.timestamp * 1e9);
    const ros::Time received = Stamp(stamp + 3000000);
    const cv::Mat grey = cv::imread(sequence.directory + "/" + frame.image_path, cv::IMREAD_UNCHANGED);
    if (encoding == "png") {
      sensor_msgs::CompressedImage image;
      image.header.stamp = Stamp(stamp);
      image.header.frame_id = "camera_optical";
      image.format = "png";
      cv::imencode(".png", grey, image.data);
      bag.write("/camera/image_raw/compressed", received, image);
    } else {
      sensor_msgs::Image image;
      image.header.stamp = Stamp(stamp);
      image.header.frame_id = "camera_optical";
      cv::Mat pixels = grey;
      if (encoding == "rgb8") cv::cvtColor(grey, pixels, cv::COLOR_GRAY2RGB);
      image.height = pixels.rows;
      image.width = pixels.cols;
      image.encoding = encoding;
      image.step = static_cast<std::uint32_t>(pixels.cols * pixels.channels());
      image.data.assign(pixels.data, pixels.data + pixels.total() * pixels.channels());
      bag.write("/camera/image_raw", received, image);
    }
    sensor_msgs::CameraInfo info;
    info.header.stamp = Stamp(stamp);
    info.header.frame_id = "camera_optical";
    info.width = camera.width;
    info.height = camera.height;
    info.distortion_model = "plumb_bob";
    info.D.assign(camera.distortion.begin(), camera.distortion.end());
    info.K = {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
    bag.write("/camera/camera_info", received, info);
    nav_msgs::Odometry odometry;
    odometry.header.stamp = Stamp(stamp);
    odometry.header.frame_id = "odom";
    odometry.child_frame_id = "base_link";
    SetPose(frame.world_T_base_odometry, &odometry.pose.pose.position, &odometry.pose.pose.orientation);
    bag.write("/odom", received, odometry);
    geometry_msgs::PoseStamped truth;
    truth.header.stamp = Stamp(stamp);
    truth.header.frame_id = "map";
    SetPose(*frame.world_T_base_groundtruth, &truth.pose.position, &truth.pose.orientation);
    bag.write("/groundtruth", received, truth);
  }
  bag.close();
}

class Rosbag1RoundTrip : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = sfm::testing::MakeScratchDir("rosbag1_round_trip");
    const std::string dir = scratch_ + "/sequence";
    ASSERT_EQ(std::system((std::string(SFM_MAKE_SEQUENCE_BINARY) + " --scene corridor --frames 6 --output " +
                           dir + " >/dev/null 2>&1")
                              .c_str()),
              0);
    ASSERT_TRUE(ReadSequence(dir, &sequence_).ok());
    // ROS 1 stamps start at 1 s (time 0 is "no stamp"): the comparison shifts the original by it.
    for (Frame& frame : sequence_.frames) frame.timestamp += 1;
  }
  testing::AppRun Import(const std::string& arguments) {
    return testing::RunProgram(SFM_IMPORT_SEQUENCE_BINARY, "--format rosbag " + arguments, scratch_);
  }
  std::string scratch_;
  Sequence sequence_;
};

// Raw mono8 and rgb8 images and PNG-compressed ones, in bags with uncompressed, LZ4 and BZ2
// chunks: the sequence comes back with images bit-identical and poses within 1e-9.
TEST_F(Rosbag1RoundTrip, ImagesBitIdenticalPosesWithin1e9) {
  struct Variant {
    std::string name, encoding;
    rosbag::compression::CompressionType compression;
    bool colour;
  };
  const std::vector<Variant> variants = {
      {"mono8_uncompressed", "mono8", rosbag::compression::Uncompressed, false},
      {"rgb8_lz4", "rgb8", rosbag::compression::LZ4, true},
      {"png_bz2", "png", rosbag::compression::BZ2, false}};
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    const std::string bag = scratch_ + "/" + v.name + ".bag";
    WriteRos1Bag(sequence_, bag, v.encoding, v.compression);
    const std::string output = scratch_ + "/" + v.name + "_imported";
    const testing::AppRun run =
        Import("--input " + bag + " --output " + output + " --groundtruth_topic /groundtruth");
    ASSERT_EQ(run.exit_status, 0) << run.errors;
    testing::ExpectSameSequence(sequence_, output, v.colour);
    EXPECT_THAT(sfm::testing::ReadFile(output + "/import_notes.txt"), HasSubstr("format: ROS 1 bag"));
  }
}

// A truncated bag and a missing topic: exit 1, one line naming the bag and the problem, no output.
TEST_F(Rosbag1RoundTrip, BadBagsAreOneLineAndNoOutput) {
  const std::string bag = scratch_ + "/good.bag";
  WriteRos1Bag(sequence_, bag, "mono8", rosbag::compression::LZ4);
  const std::string bytes = sfm::testing::ReadFile(bag);
  const std::string truncated = scratch_ + "/truncated.bag";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string output = scratch_ + "/bad_imported";
  struct Case {
    std::string input, flags, expected;
  };
  const std::vector<Case> cases = {
      {truncated, "", "cannot be read as a ROS 1 bag"},
      {bag, "--odometry_topic /wheel_odom", "no topic /wheel_odom (odometry topics: /odom"},
      {scratch_ + "/missing.bag", "", "bag does not exist"}};
  for (const Case& c : cases) {
    const testing::AppRun run = Import("--input " + c.input + " --output " + output + " " + c.flags);
    EXPECT_EQ(run.exit_status, 1) << c.input;
    EXPECT_EQ(std::count(run.errors.begin(), run.errors.end(), '\n'), 1) << run.errors;
    EXPECT_THAT(run.errors, HasSubstr("import_sequence: " + c.input + ": ")) << run.errors;
    EXPECT_THAT(run.errors, HasSubstr(c.expected)) << run.errors;
    EXPECT_FALSE(fs::exists(output));
  }
}

}  // namespace
}  // namespace sfm

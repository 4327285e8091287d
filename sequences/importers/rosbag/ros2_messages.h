// The ROS 2 messages the bag importer reads, decoded from their CDR serialization (OMG CDR with
// the 4-byte encapsulation header ROS 2 writes, little or big endian) with eProsima Fast CDR.
// Field order is that of the .msg definitions (sensor_msgs, nav_msgs, geometry_msgs, tf2_msgs).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

// ROS message type names, as rosbag2 writes them in metadata.yaml and MCAP schemas.
inline constexpr const char* kRosImage = "sensor_msgs/msg/Image";
inline constexpr const char* kRosCompressedImage = "sensor_msgs/msg/CompressedImage";
inline constexpr const char* kRosCameraInfo = "sensor_msgs/msg/CameraInfo";
inline constexpr const char* kRosOdometry = "nav_msgs/msg/Odometry";
inline constexpr const char* kRosPoseStamped = "geometry_msgs/msg/PoseStamped";
inline constexpr const char* kRosTransformStamped = "geometry_msgs/msg/TransformStamped";
inline constexpr const char* kRosTfMessage = "tf2_msgs/msg/TFMessage";

struct RosHeader {
  std::int64_t stamp = 0;  // nanoseconds (builtin_interfaces/Time sec * 1e9 + nanosec)
  std::string frame_id;
};

struct RosImage {  // sensor_msgs/msg/Image
  RosHeader header;
  std::uint32_t height = 0, width = 0;
  std::string encoding;  // "mono8", "rgb8", "bgr8", "mono16", ...
  bool big_endian = false;
  std::uint32_t step = 0;  // bytes per row
  std::vector<std::uint8_t> data;
};

struct RosCompressedImage {  // sensor_msgs/msg/CompressedImage
  RosHeader header;
  std::string format;  // e.g. "jpeg", "png", "bgr8; jpeg compressed bgr8"
  std::vector<std::uint8_t> data;
};

// nav_msgs/msg/Odometry (pose.pose), geometry_msgs/msg/PoseStamped (pose) or
// geometry_msgs/msg/TransformStamped (transform): the pose of child_frame_id in header.frame_id,
// parent_T_child. PoseStamped has no child frame: child_frame_id is then empty.
struct RosStampedPose {
  RosHeader header;
  std::string child_frame_id;
  Pose3 parent_T_child;
};

struct RosCameraInfo {  // sensor_msgs/msg/CameraInfo
  RosHeader header;
  std::uint32_t height = 0, width = 0;
  std::string distortion_model;  // "plumb_bob", "equidistant", "rational_polynomial", ...
  std::vector<double> d;
  std::array<double, 9> k{};  // row-major 3x3
};

// Each fails with "<what>: <problem>" (a truncated or malformed serialization, a quaternion that
// is not unit within 1e-3 or not finite).
Status DecodeRosHeaderOnly(const std::uint8_t* data, std::size_t size, const std::string& what,
                           RosHeader* header);
Status DecodeRosImage(const std::uint8_t* data, std::size_t size, const std::string& what, RosImage* image);
Status DecodeRosCompressedImage(const std::uint8_t* data, std::size_t size, const std::string& what,
                                RosCompressedImage* image);
// `type`: kRosOdometry, kRosPoseStamped or kRosTransformStamped.
Status DecodeRosStampedPose(const std::string& type, const std::uint8_t* data, std::size_t size,
                            const std::string& what, RosStampedPose* pose);
Status DecodeRosTfMessage(const std::uint8_t* data, std::size_t size, const std::string& what,
                          std::vector<RosStampedPose>* transforms);
Status DecodeRosCameraInfo(const std::uint8_t* data, std::size_t size, const std::string& what,
                           RosCameraInfo* info);

// True for the types DecodeRosStampedPose reads.
bool IsRosPoseType(const std::string& type);

}  // namespace sfm

// A robot's recording (a ROS 2 or a ROS 1 bag) as the bag importer reads it: its topics, and its
// messages decoded into the structs of ros2_messages.h. Type names are ROS 2's
// ("sensor_msgs/msg/Image"); a ROS 1 bag's "sensor_msgs/Image" is given as such.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sequences/importers/rosbag/ros2_messages.h"
#include "sequences/importers/rosbag/rosbag2_bag.h"
#include "util/status.h"

namespace sfm {

// One message during Recording::ReadMessages; each decoder fails (naming the bag, the topic and the
// message) when the message is not of that type or does not decode.
class RecordedMessage {
 public:
  virtual ~RecordedMessage() = default;
  virtual Status ImageHeader(RosHeader* header) const = 0;  // of an Image or CompressedImage
  virtual Status Image(RosImage* image) const = 0;
  virtual Status CompressedImage(RosCompressedImage* image) const = 0;
  virtual Status StampedPose(RosStampedPose* pose) const = 0;  // Odometry, PoseStamped, TransformStamped
  virtual Status TfMessage(std::vector<RosStampedPose>* transforms) const = 0;
  virtual Status CameraInfo(RosCameraInfo* info) const = 0;
};

class Recording {
 public:
  using MessageCallback = std::function<Status(const BagTopic& topic, const RecordedMessage& message)>;

  virtual ~Recording() = default;
  virtual const std::string& path() const = 0;
  virtual std::string format() const = 0;  // for import_notes.txt, e.g. "ROS 2 bag (mcap)"
  // Every message in storage order; during the call for a message, topic.count is the number of
  // that topic's messages met so far (so count - 1 is its index). topics() is complete after it.
  virtual Status ReadMessages(const MessageCallback& on_message) = 0;
  virtual const std::vector<BagTopic>& topics() const = 0;

  int FindTopic(const std::string& name) const {
    for (size_t i = 0; i < topics().size(); ++i) {
      if (topics()[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }
};

}  // namespace sfm

// The ROS 2 bag as a Recording: Rosbag2Bag's serialized messages decoded from CDR.
#include "sequences/importers/rosbag/bag_importer.h"
#include "sequences/importers/rosbag/ros2_messages.h"
#include "sequences/importers/rosbag/rosbag2_bag.h"

namespace sfm {
namespace {

class Rosbag2Message : public RecordedMessage {
 public:
  Rosbag2Message(const BagTopic& topic, const BagMessage& message, const std::string& what)
      : topic_(topic), message_(message), what_(what) {}
  Status ImageHeader(RosHeader* header) const override {
    return DecodeRosHeaderOnly(message_.data, message_.size, what_, header);
  }
  Status Image(RosImage* image) const override {
    return DecodeRosImage(message_.data, message_.size, what_, image);
  }
  Status CompressedImage(RosCompressedImage* image) const override {
    return DecodeRosCompressedImage(message_.data, message_.size, what_, image);
  }
  Status StampedPose(RosStampedPose* pose) const override {
    return DecodeRosStampedPose(topic_.type, message_.data, message_.size, what_, pose);
  }
  Status TfMessage(std::vector<RosStampedPose>* transforms) const override {
    return DecodeRosTfMessage(message_.data, message_.size, what_, transforms);
  }
  Status CameraInfo(RosCameraInfo* info) const override {
    return DecodeRosCameraInfo(message_.data, message_.size, what_, info);
  }

 private:
  const BagTopic& topic_;
  const BagMessage& message_;
  const std::string& what_;
};

class Rosbag2Recording : public Recording {
 public:
  Status Open(const std::string& path) { return bag_.Open(path); }
  const std::string& path() const override { return bag_.path(); }
  std::string format() const override { return "ROS 2 bag (" + bag_.storage() + ")"; }
  const std::vector<BagTopic>& topics() const override { return bag_.topics(); }
  Status ReadMessages(const MessageCallback& on_message) override {
    return bag_.ReadMessages([&](const BagTopic& topic, const BagMessage& message) {
      const std::string what =
          bag_.path() + ": " + topic.name + ": message " + std::to_string(topic.count - 1);
      return on_message(topic, Rosbag2Message(topic, message, what));
    });
  }

 private:
  Rosbag2Bag bag_;
};

}  // namespace

Status ImportRosbag2(const std::string& bag_path, const BagImportOptions& options,
                     const std::string& output_dir, BagImportSummary* summary) {
  Rosbag2Recording recording;
  SFM_RETURN_IF_ERROR(recording.Open(bag_path));
  return ImportRecording(&recording, options, output_dir, summary);
}

}  // namespace sfm

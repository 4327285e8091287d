#include "sequences/importers/rosbag/rosbag1_recording.h"

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>

#include <filesystem>
#include <map>

namespace sfm {
namespace {

std::string Ros2TypeName(const std::string& ros1_type) {
  const size_t slash = ros1_type.find('/');
  if (slash == std::string::npos) return ros1_type;
  return ros1_type.substr(0, slash) + "/msg/" + ros1_type.substr(slash + 1);
}

RosHeader Header(const std_msgs::Header& header) {
  RosHeader out;
  out.stamp = std::int64_t{header.stamp.sec} * 1000000000 + header.stamp.nsec;
  out.frame_id = header.frame_id;
  return out;
}

Pose3 Pose(const geometry_msgs::Point& t, const geometry_msgs::Quaternion& q) {
  return Pose3(Eigen::Quaterniond(q.w, q.x, q.y, q.z), Eigen::Vector3d(t.x, t.y, t.z));
}
Pose3 Pose(const geometry_msgs::Vector3& t, const geometry_msgs::Quaternion& q) {
  return Pose3(Eigen::Quaterniond(q.w, q.x, q.y, q.z), Eigen::Vector3d(t.x, t.y, t.z));
}

Status CheckPose(const Pose3& pose, const std::string& what) {
  if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite()) {
    return Status::Error(what + ": pose is not finite");
  }
  if (std::abs(pose.rotation.norm() - 1) > 1e-3)
    return Status::Error(what + ": quaternion is not a rotation");
  return Status::Ok();
}

// The md5sum of the message definition our headers were compiled with, by ROS 1 type name.
const std::map<std::string, std::string>& KnownMd5Sums() {
  static const std::map<std::string, std::string> sums = {
      {"sensor_msgs/Image", ros::message_traits::MD5Sum<sensor_msgs::Image>::value()},
      {"sensor_msgs/CompressedImage", ros::message_traits::MD5Sum<sensor_msgs::CompressedImage>::value()},
      {"sensor_msgs/CameraInfo", ros::message_traits::MD5Sum<sensor_msgs::CameraInfo>::value()},
      {"nav_msgs/Odometry", ros::message_traits::MD5Sum<nav_msgs::Odometry>::value()},
      {"geometry_msgs/PoseStamped", ros::message_traits::MD5Sum<geometry_msgs::PoseStamped>::value()},
      {"geometry_msgs/TransformStamped",
       ros::message_traits::MD5Sum<geometry_msgs::TransformStamped>::value()},
      {"tf2_msgs/TFMessage", ros::message_traits::MD5Sum<tf2_msgs::TFMessage>::value()},
  };
  return sums;
}

class Rosbag1Message : public RecordedMessage {
 public:
  Rosbag1Message(const rosbag::MessageInstance& message, const std::string& what)
      : message_(message), what_(what) {}

  Status ImageHeader(RosHeader* header) const override {
    if (auto image = message_.instantiate<sensor_msgs::Image>()) {
      *header = Header(image->header);
      return Status::Ok();
    }
    if (auto image = message_.instantiate<sensor_msgs::CompressedImage>()) {
      *header = Header(image->header);
      return Status::Ok();
    }
    return NotA("sensor_msgs/Image");
  }
  Status Image(RosImage* out) const override {
    const auto image = message_.instantiate<sensor_msgs::Image>();
    if (!image) return NotA("sensor_msgs/Image");
    out->header = Header(image->header);
    out->height = image->height;
    out->width = image->width;
    out->encoding = image->encoding;
    out->big_endian = image->is_bigendian != 0;
    out->step = image->step;
    out->data = image->data;
    return Status::Ok();
  }
  Status CompressedImage(RosCompressedImage* out) const override {
    const auto image = message_.instantiate<sensor_msgs::CompressedImage>();
    if (!image) return NotA("sensor_msgs/CompressedImage");
    out->header = Header(image->header);
    out->format = image->format;
    out->data = image->data;
    return Status::Ok();
  }
  Status StampedPose(RosStampedPose* out) const override {
    if (auto odometry = message_.instantiate<nav_msgs::Odometry>()) {
      out->header = Header(odometry->header);
      out->child_frame_id = odometry->child_frame_id;
      out->parent_T_child = Pose(odometry->pose.pose.position, odometry->pose.pose.orientation);
    } else if (auto pose = message_.instantiate<geometry_msgs::PoseStamped>()) {
      out->header = Header(pose->header);
      out->child_frame_id.clear();
      out->parent_T_child = Pose(pose->pose.position, pose->pose.orientation);
    } else if (auto transform = message_.instantiate<geometry_msgs::TransformStamped>()) {
      *out = Transform(*transform);
    } else {
      return NotA("pose");
    }
    return CheckPose(out->parent_T_child, what_);
  }
  Status TfMessage(std::vector<RosStampedPose>* out) const override {
    const auto message = message_.instantiate<tf2_msgs::TFMessage>();
    if (!message) return NotA("tf2_msgs/TFMessage");
    out->clear();
    for (const geometry_msgs::TransformStamped& transform : message->transforms) {
      out->push_back(Transform(transform));
      SFM_RETURN_IF_ERROR(CheckPose(out->back().parent_T_child, what_));
    }
    return Status::Ok();
  }
  Status CameraInfo(RosCameraInfo* out) const override {
    const auto info = message_.instantiate<sensor_msgs::CameraInfo>();
    if (!info) return NotA("sensor_msgs/CameraInfo");
    out->header = Header(info->header);
    out->height = info->height;
    out->width = info->width;
    out->distortion_model = info->distortion_model;
    out->d = info->D;
    std::copy(info->K.begin(), info->K.end(), out->k.begin());
    return Status::Ok();
  }

 private:
  static RosStampedPose Transform(const geometry_msgs::TransformStamped& transform) {
    RosStampedPose out;
    out.header = Header(transform.header);
    out.child_frame_id = transform.child_frame_id;
    out.parent_T_child = Pose(transform.transform.translation, transform.transform.rotation);
    return out;
  }
  Status NotA(const std::string& type) const {
    return Status::Error(what_ + ": not a " + type + " (" + message_.getDataType() + ")");
  }

  const rosbag::MessageInstance& message_;
  const std::string& what_;
};

class Rosbag1Recording : public Recording {
 public:
  Status Open(const std::string& path) {
    path_ = path;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return Status::Error(path + ": bag does not exist");
    try {
      bag_.open(path, rosbag::bagmode::Read);
    } catch (const std::exception& e) {
      return Status::Error(path + ": cannot be read as a ROS 1 bag (" + std::string(e.what()) + ")");
    }
    return Status::Ok();
  }
  const std::string& path() const override { return path_; }
  std::string format() const override { return "ROS 1 bag"; }
  const std::vector<BagTopic>& topics() const override { return topics_; }

  Status ReadMessages(const MessageCallback& on_message) override {
    topics_.clear();
    try {
      rosbag::View view(bag_);
      std::map<std::string, int> index;
      for (const rosbag::ConnectionInfo* connection : view.getConnections()) {
        if (index.count(connection->topic) == 0) {
          index[connection->topic] = static_cast<int>(topics_.size());
          BagTopic topic;
          topic.name = connection->topic;
          topic.type = Ros2TypeName(connection->datatype);
          topic.serialization_format = "ros1";
          topics_.push_back(topic);
        }
        const auto known = KnownMd5Sums().find(connection->datatype);
        if (known != KnownMd5Sums().end() && known->second != "*" && connection->md5sum != known->second) {
          topics_[index[connection->topic]].problem = "message definition of " + connection->datatype +
                                                      " differs from ROS 1's (md5sum " + connection->md5sum +
                                                      ")";
        }
      }
      for (const rosbag::MessageInstance& message : view) {
        BagTopic& topic = topics_[index.at(message.getTopic())];
        ++topic.count;
        const std::string what = path_ + ": " + topic.name + ": message " + std::to_string(topic.count - 1);
        SFM_RETURN_IF_ERROR(on_message(topic, Rosbag1Message(message, what)));
      }
    } catch (const std::exception& e) {
      return Status::Error(path_ + ": cannot be read as a ROS 1 bag (" + std::string(e.what()) + ")");
    }
    return Status::Ok();
  }

 private:
  std::string path_;
  rosbag::Bag bag_;
  std::vector<BagTopic> topics_;
};

}  // namespace

Status ImportRosbag1(const std::string& bag_path, const BagImportOptions& options,
                     const std::string& output_dir, BagImportSummary* summary) {
  Rosbag1Recording recording;
  SFM_RETURN_IF_ERROR(recording.Open(bag_path));
  return ImportRecording(&recording, options, output_dir, summary);
}

}  // namespace sfm

#include "sequences/importers/rosbag/ros2_messages.h"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include <cmath>

namespace sfm {
namespace {

using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::FastBuffer;

// A CDR stream over one message. Fast CDR's buffer type takes a mutable pointer; it is only read.
class Decoder {
 public:
  Decoder(const std::uint8_t* data, std::size_t size)
      : size_(size),
        buffer_(const_cast<char*>(reinterpret_cast<const char*>(data)), size),
        cdr_(buffer_, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR) {
    // The encapsulation header (representation identifier and options) sets the endianness.
    cdr_.read_encapsulation();
  }
  Cdr& cdr() { return cdr_; }

  void Header(RosHeader* header) {
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    cdr_.deserialize(sec);
    cdr_.deserialize(nanosec);
    header->stamp = std::int64_t{sec} * 1000000000 + nanosec;
    cdr_.deserialize(header->frame_id);
  }
  // sequence<uint8>: a length, then the bytes, copied in one piece.
  void Bytes(std::vector<std::uint8_t>* bytes) {
    std::uint32_t length = 0;
    cdr_.deserialize(length);
    if (length > size_ - cdr_.getSerializedDataLength()) {
      throw eprosima::fastcdr::exception::NotEnoughMemoryException("byte sequence longer than the message");
    }
    bytes->resize(length);
    if (length > 0) cdr_.deserializeArray(bytes->data(), length);
  }
  // geometry_msgs/Point (or Vector3) then geometry_msgs/Quaternion: x y z, then x y z w.
  void Pose(Pose3* pose) {
    double values[7];
    cdr_.deserializeArray(values, 7);
    pose->translation = Eigen::Vector3d(values[0], values[1], values[2]);
    pose->rotation = Eigen::Quaterniond(values[6], values[3], values[4], values[5]);
  }

 private:
  std::size_t size_;
  FastBuffer buffer_;
  Cdr cdr_;
};

// Runs `decode` and turns Fast CDR's exceptions (reading past the end, bad values) into a Status.
template <typename Decode>
Status Run(const std::uint8_t* data, std::size_t size, const std::string& what, const Decode& decode) {
  if (size < 4)
    return Status::Error(what + ": message of " + std::to_string(size) + " bytes has no CDR header");
  try {
    Decoder decoder(data, size);
    decode(&decoder);
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    return Status::Error(what + ": malformed CDR message (" + e.what() + ")");
  } catch (const std::exception& e) {
    return Status::Error(what + ": malformed CDR message (" + e.what() + ")");
  }
  return Status::Ok();
}

Status CheckPose(const Pose3& pose, const std::string& what) {
  if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite()) {
    return Status::Error(what + ": pose is not finite");
  }
  if (std::abs(pose.rotation.norm() - 1) > 1e-3) {
    return Status::Error(what + ": quaternion of norm " + std::to_string(pose.rotation.norm()) +
                         " is not a rotation");
  }
  return Status::Ok();
}

}  // namespace

bool IsRosPoseType(const std::string& type) {
  return type == kRosOdometry || type == kRosPoseStamped || type == kRosTransformStamped;
}

Status DecodeRosHeaderOnly(const std::uint8_t* data, std::size_t size, const std::string& what,
                           RosHeader* header) {
  return Run(data, size, what, [&](Decoder* decoder) { decoder->Header(header); });
}

Status DecodeRosImage(const std::uint8_t* data, std::size_t size, const std::string& what, RosImage* image) {
  return Run(data, size, what, [&](Decoder* decoder) {
    Cdr& cdr = decoder->cdr();
    decoder->Header(&image->header);
    cdr.deserialize(image->height);
    cdr.deserialize(image->width);
    cdr.deserialize(image->encoding);
    std::uint8_t big_endian = 0;
    cdr.deserialize(big_endian);
    image->big_endian = big_endian != 0;
    cdr.deserialize(image->step);
    decoder->Bytes(&image->data);
  });
}

Status DecodeRosCompressedImage(const std::uint8_t* data, std::size_t size, const std::string& what,
                                RosCompressedImage* image) {
  return Run(data, size, what, [&](Decoder* decoder) {
    decoder->Header(&image->header);
    decoder->cdr().deserialize(image->format);
    decoder->Bytes(&image->data);
  });
}

Status DecodeRosStampedPose(const std::string& type, const std::uint8_t* data, std::size_t size,
                            const std::string& what, RosStampedPose* pose) {
  SFM_RETURN_IF_ERROR(Run(data, size, what, [&](Decoder* decoder) {
    decoder->Header(&pose->header);
    // Odometry: header, child_frame_id, pose (PoseWithCovariance: Pose, then the covariance).
    // TransformStamped: header, child_frame_id, transform (Vector3, Quaternion: the same layout as
    // a Pose). PoseStamped: header, pose.
    if (type != kRosPoseStamped) decoder->cdr().deserialize(pose->child_frame_id);
    decoder->Pose(&pose->parent_T_child);
  }));
  return CheckPose(pose->parent_T_child, what);
}

Status DecodeRosTfMessage(const std::uint8_t* data, std::size_t size, const std::string& what,
                          std::vector<RosStampedPose>* transforms) {
  SFM_RETURN_IF_ERROR(Run(data, size, what, [&](Decoder* decoder) {
    std::uint32_t count = 0;
    decoder->cdr().deserialize(count);
    if (count > size)
      throw eprosima::fastcdr::exception::NotEnoughMemoryException("more transforms than bytes");
    transforms->resize(count);
    for (RosStampedPose& transform : *transforms) {
      decoder->Header(&transform.header);
      decoder->cdr().deserialize(transform.child_frame_id);
      decoder->Pose(&transform.parent_T_child);
    }
  }));
  for (const RosStampedPose& transform : *transforms)
    SFM_RETURN_IF_ERROR(CheckPose(transform.parent_T_child, what));
  return Status::Ok();
}

Status DecodeRosCameraInfo(const std::uint8_t* data, std::size_t size, const std::string& what,
                           RosCameraInfo* info) {
  return Run(data, size, what, [&](Decoder* decoder) {
    Cdr& cdr = decoder->cdr();
    decoder->Header(&info->header);
    cdr.deserialize(info->height);
    cdr.deserialize(info->width);
    cdr.deserialize(info->distortion_model);
    std::uint32_t count = 0;
    cdr.deserialize(count);
    if (count > size)
      throw eprosima::fastcdr::exception::NotEnoughMemoryException("more coefficients than bytes");
    info->d.resize(count);
    if (count > 0) cdr.deserializeArray(info->d.data(), count);
    cdr.deserializeArray(info->k.data(), 9);
  });
}

}  // namespace sfm

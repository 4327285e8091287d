// Writing ROS 2 bags for the importer's tests: a minimal MCAP writer (the record layouts of the
// public MCAP specification, chunks compressed with libzstd / liblz4, CRC-32 from zlib) and a
// sqlite3 one, and the CDR serialization (Fast CDR) of the messages the importer reads. The
// reader is also tested on bags that rosbag2 itself wrote (../shared/data/rosbag2-test-bags),
// so the two are not checked only against each other.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pose.h"

namespace sfm::testing {

struct BagMessageSpec {
  std::string topic, type;
  std::int64_t log_time = 0;       // ns
  std::vector<std::uint8_t> data;  // CDR
};

struct McapWriteOptions {
  bool chunked = true;
  std::string compression;            // "", "zstd", "lz4", or anything else (written as is, for error tests)
  bool summary = true;                // summary section (schemas, channels, statistics) and its CRC
  std::size_t chunk_bytes = 1 << 18;  // uncompressed records per chunk (about)
  std::string message_encoding = "cdr";
  std::string schema_encoding = "ros2msg";
  std::vector<std::string> empty_topics;  // "topic type" channels without messages
};

// The bytes of an MCAP file holding the messages in order.
std::string WriteMcap(const std::vector<BagMessageSpec>& messages, const McapWriteOptions& options);
// A rosbag2 sqlite3 database (topics and messages tables) at `path`; true on success.
bool WriteSqliteBag(const std::string& path, const std::vector<BagMessageSpec>& messages);
// metadata.yaml of a bag folder with one storage file.
std::string Rosbag2Metadata(const std::string& storage, const std::string& file,
                            const std::vector<BagMessageSpec>& messages);

// CDR of the messages (ROS 2 field order, little-endian encapsulation).
std::vector<std::uint8_t> CdrImage(std::int64_t stamp, const std::string& frame, int width, int height,
                                   const std::string& encoding, std::uint32_t step,
                                   const std::vector<std::uint8_t>& pixels);
std::vector<std::uint8_t> CdrCompressedImage(std::int64_t stamp, const std::string& frame,
                                             const std::string& format,
                                             const std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> CdrOdometry(std::int64_t stamp, const std::string& frame, const std::string& child,
                                      const Pose3& pose);
std::vector<std::uint8_t> CdrPoseStamped(std::int64_t stamp, const std::string& frame, const Pose3& pose);
std::vector<std::uint8_t> CdrTfMessage(const std::vector<std::pair<std::string, std::string>>& parent_child,
                                       const std::vector<Pose3>& parent_T_child);
std::vector<std::uint8_t> CdrCameraInfo(std::int64_t stamp, const std::string& frame, int width, int height,
                                        const std::string& model, const std::vector<double>& d, double fx,
                                        double fy, double cx, double cy);

}  // namespace sfm::testing

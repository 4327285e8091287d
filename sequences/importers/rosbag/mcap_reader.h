// A reader of MCAP files (the default storage of ROS 2 bags), written from the public MCAP
// specification (mcap.dev/spec, format version "0"): no packaged MCAP reader exists in the
// registries the project uses (docs/importers.md).
//
// It reads the data section front to back: records outside and inside chunks, chunks compressed
// with zstd or lz4 (LZ4 frame format) or not at all, each chunk's CRC-32 of its uncompressed
// records and the data section's CRC-32 checked where the file gives them (a zero CRC means
// "not computed"). The summary section, when the file has one, is read and its CRC-32 checked on
// opening; files without one (unindexed, or a recording cut short) are read the same way.
#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "util/status.h"

namespace sfm {

struct McapSchema {
  std::uint16_t id = 0;
  std::string name;      // e.g. "sensor_msgs/msg/Image"
  std::string encoding;  // e.g. "ros2msg"
  std::string data;      // the schema text
};

struct McapChannel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // e.g. "cdr"
  std::map<std::string, std::string> metadata;
};

struct McapMessage {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      // nanoseconds
  std::uint64_t publish_time = 0;  // nanoseconds
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// What the summary section says, when the file has one.
struct McapSummary {
  bool present = false;
  std::map<std::uint16_t, McapSchema> schemas;
  std::map<std::uint16_t, McapChannel> channels;
  bool has_statistics = false;
  std::uint64_t message_count = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
  std::uint32_t chunk_count = 0;
};

class McapReader {
 public:
  // Called for each message with its channel and the channel's schema (nullptr when it has none).
  using MessageCallback =
      std::function<Status(const McapChannel& channel, const McapSchema* schema, const McapMessage& message)>;

  // Opens the file: checks the magic at its start, and at its end the footer, the summary section
  // and its CRC when present. Fails, naming the file, on a file that is not MCAP, an unsupported
  // major version, a corrupt footer or summary, or a summary CRC mismatch.
  Status Open(const std::string& path);

  const std::string& path() const { return path_; }
  const std::string& profile() const { return profile_; }  // the header's profile, "ros2" for rosbag2
  const McapSummary& summary() const { return summary_; }

  // Reads every message of the data section in file order (inside a chunk: the chunk's order),
  // calling `on_message` for each; a callback error stops the read and is returned. Fails, naming
  // the file and the byte offset, on a truncated record or chunk, an unknown chunk compression, a
  // chunk that does not decompress to its stated size, a chunk or data section CRC mismatch, a
  // message on a channel not defined before it, or a malformed record. Channels and schemas met
  // in the data section are added to channels() / schemas().
  Status ReadMessages(const MessageCallback& on_message);

  const std::map<std::uint16_t, McapChannel>& channels() const { return channels_; }
  const std::map<std::uint16_t, McapSchema>& schemas() const { return schemas_; }

 private:
  Status HandleRecord(std::uint8_t opcode, const std::uint8_t* content, std::uint64_t length,
                      std::uint64_t offset, bool in_chunk, const MessageCallback& on_message);
  Status ReadChunk(const std::uint8_t* content, std::uint64_t length, std::uint64_t offset,
                   const MessageCallback& on_message);
  Status ReadSummary(std::uint64_t summary_start, std::uint64_t summary_end, std::uint32_t summary_crc);
  Status Error(std::uint64_t offset, const std::string& problem) const;

  std::string path_;
  std::uint64_t file_size_ = 0;
  std::uint64_t data_end_ = 0;  // where the summary (or the footer) starts: the data section ends before
  std::string profile_;
  McapSummary summary_;
  std::map<std::uint16_t, McapChannel> channels_;
  std::map<std::uint16_t, McapSchema> schemas_;
  std::vector<std::uint8_t> decompressed_;
};

}  // namespace sfm

// A ROS 2 bag as rosbag2 records it: a folder with metadata.yaml (read with yaml-cpp) and one or
// more storage files, MCAP (mcap_reader.h) or sqlite3 (.db3, read with libsqlite3); or one
// storage file alone. Gives the topics with their types and the messages' serialized bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "util/status.h"

namespace sfm {

struct BagTopic {
  std::string name;                  // e.g. "/camera/image_raw"
  std::string type;                  // e.g. "sensor_msgs/msg/Image"
  std::string serialization_format;  // "cdr" for every topic this importer can decode
  // Empty when the topic's messages are CDR of a ROS 2 message schema; else why they are not
  // (e.g. "message encoding 'json', expected cdr"), for the importer to report when it needs the topic.
  std::string problem;
  std::uint64_t count = 0;  // messages met by ReadMessages
};

struct BagMessage {
  std::int64_t log_time = 0;  // nanoseconds, when the recorder received it
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

class Rosbag2Bag {
 public:
  using MessageCallback = std::function<Status(const BagTopic& topic, const BagMessage& message)>;

  // `path`: a bag folder (metadata.yaml beside its storage files; a folder without metadata.yaml
  // holding exactly one .mcap or .db3 file is read as that file), or one .mcap or .db3 file.
  // Fails, naming the path, on anything else, a malformed metadata.yaml, an unknown storage
  // identifier, a compressed bag (compression_format in metadata.yaml), or a storage file that
  // does not open (McapReader::Open, sqlite3).
  Status Open(const std::string& path);

  const std::string& path() const { return path_; }
  const std::string& storage() const { return storage_; }  // "mcap" or "sqlite3"
  const std::vector<std::string>& files() const { return files_; }

  // Every message of every storage file, in each file's order; topics() is rebuilt as they are
  // met (a topic that metadata.yaml lists without messages is kept with count 0). Fails on the
  // storage's errors, naming the file.
  Status ReadMessages(const MessageCallback& on_message);

  const std::vector<BagTopic>& topics() const { return topics_; }
  // The index into topics() of `name`, or -1.
  int FindTopic(const std::string& name) const;

 private:
  BagTopic* AddTopic(const BagTopic& topic);
  Status ReadMcap(const std::string& file, const MessageCallback& on_message);
  Status ReadSqlite(const std::string& file, const MessageCallback& on_message);

  std::string path_;
  std::string storage_;
  std::vector<std::string> files_;
  std::vector<BagTopic> listed_;  // from metadata.yaml
  std::vector<BagTopic> topics_;
};

}  // namespace sfm

#include "sequences/importers/rosbag/rosbag2_bag.h"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include "sequences/importers/rosbag/mcap_reader.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

std::string Extension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension;
}

// Why a topic's messages cannot be decoded as ROS 2 CDR, or "".
std::string EncodingProblem(const std::string& message_encoding, const std::string& schema_encoding,
                            bool has_schema) {
  if (message_encoding != "cdr") return "message encoding '" + message_encoding + "', expected cdr";
  if (!has_schema) return "no schema";
  if (schema_encoding != "ros2msg" && schema_encoding != "ros2idl") {
    return "schema encoding '" + schema_encoding + "', expected ros2msg or ros2idl";
  }
  return "";
}

std::string YamlString(const YAML::Node& node) {
  return node && node.IsScalar() ? node.as<std::string>() : "";
}

}  // namespace

int Rosbag2Bag::FindTopic(const std::string& name) const {
  for (size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

BagTopic* Rosbag2Bag::AddTopic(const BagTopic& topic) {
  const int index = FindTopic(topic.name);
  if (index >= 0) return &topics_[index];
  topics_.push_back(topic);
  topics_.back().count = 0;
  return &topics_.back();
}

Status Rosbag2Bag::Open(const std::string& path) {
  path_ = path;
  files_.clear();
  listed_.clear();
  topics_.clear();
  std::error_code error;
  const fs::path input(path);
  if (fs::is_directory(input, error)) {
    const fs::path metadata = input / "metadata.yaml";
    if (!fs::exists(metadata, error)) {
      std::vector<fs::path> storage_files;
      for (const fs::directory_entry& entry : fs::directory_iterator(input, error)) {
        const std::string extension = Extension(entry.path());
        if (entry.is_regular_file(error) && (extension == ".mcap" || extension == ".db3")) {
          storage_files.push_back(entry.path());
        }
      }
      if (storage_files.size() != 1) {
        return Status::Error(
            path + ": a ROS 2 bag folder needs metadata.yaml (or exactly one .mcap or .db3 file; found " +
            std::to_string(storage_files.size()) + ")");
      }
      files_.push_back(storage_files[0].string());
      storage_ = Extension(storage_files[0]) == ".mcap" ? "mcap" : "sqlite3";
    } else {
      const std::string where = metadata.string() + ": ";
      try {
        const YAML::Node root = YAML::LoadFile(metadata.string());
        const YAML::Node info = root["rosbag2_bagfile_information"];
        if (!info || !info.IsMap()) return Status::Error(where + "no rosbag2_bagfile_information map");
        storage_ = YamlString(info["storage_identifier"]);
        if (storage_ != "mcap" && storage_ != "sqlite3") {
          return Status::Error(where + "storage_identifier '" + storage_ +
                               "': this importer reads mcap and sqlite3");
        }
        const std::string compression = YamlString(info["compression_format"]);
        if (!compression.empty()) {
          return Status::Error(
              where + "the bag is compressed as a whole (compression_format " + compression + ", mode " +
              YamlString(info["compression_mode"]) +
              "); decompress it first (ros2 bag convert) or record with storage compression");
        }
        const YAML::Node relative = info["relative_file_paths"];
        if (!relative || !relative.IsSequence() || relative.size() == 0) {
          return Status::Error(where + "relative_file_paths lists no storage file");
        }
        for (const YAML::Node& file : relative) {
          const fs::path file_path = input / YamlString(file);
          if (!fs::is_regular_file(file_path, error)) {
            return Status::Error(where + "storage file " + file_path.string() + " does not exist");
          }
          files_.push_back(file_path.string());
        }
        const YAML::Node topics = info["topics_with_message_count"];
        if (topics && topics.IsSequence()) {
          for (const YAML::Node& entry : topics) {
            const YAML::Node metadata_node = entry["topic_metadata"];
            if (!metadata_node) continue;
            BagTopic topic;
            topic.name = YamlString(metadata_node["name"]);
            topic.type = YamlString(metadata_node["type"]);
            topic.serialization_format = YamlString(metadata_node["serialization_format"]);
            topic.count = entry["message_count"] ? entry["message_count"].as<std::uint64_t>() : 0;
            listed_.push_back(topic);
          }
        }
      } catch (const YAML::Exception& e) {
        return Status::Error(where + "cannot be read as YAML (" + std::string(e.what()) + ")");
      }
    }
  } else if (fs::is_regular_file(input, error)) {
    const std::string extension = Extension(input);
    if (extension != ".mcap" && extension != ".db3") {
      return Status::Error(path + ": not a ROS 2 bag (expected a bag folder, a .mcap or a .db3 file)");
    }
    files_.push_back(path);
    storage_ = extension == ".mcap" ? "mcap" : "sqlite3";
  } else {
    return Status::Error(path + ": bag does not exist");
  }
  for (const std::string& file : files_) {
    if (storage_ == "mcap") {
      McapReader reader;
      SFM_RETURN_IF_ERROR(reader.Open(file));
    }
  }
  return Status::Ok();
}

Status Rosbag2Bag::ReadMessages(const MessageCallback& on_message) {
  topics_.clear();
  for (const BagTopic& topic : listed_) {
    BagTopic* added = AddTopic(topic);
    if (topic.serialization_format != "cdr") {
      added->problem = "serialization format '" + topic.serialization_format + "', expected cdr";
    }
  }
  for (const std::string& file : files_) {
    SFM_RETURN_IF_ERROR(storage_ == "mcap" ? ReadMcap(file, on_message) : ReadSqlite(file, on_message));
  }
  return Status::Ok();
}

Status Rosbag2Bag::ReadMcap(const std::string& file, const MessageCallback& on_message) {
  McapReader reader;
  SFM_RETURN_IF_ERROR(reader.Open(file));
  // Channel id -> index into topics_ (stable: topics_ only grows during the read).
  std::map<std::uint16_t, int> channel_topics;
  SFM_RETURN_IF_ERROR(reader.ReadMessages(
      [&](const McapChannel& channel, const McapSchema* schema, const McapMessage& message) {
        auto found = channel_topics.find(channel.id);
        if (found == channel_topics.end()) {
          BagTopic topic;
          topic.name = channel.topic;
          topic.type = schema != nullptr ? schema->name : "";
          topic.serialization_format = channel.message_encoding;
          topic.problem = EncodingProblem(channel.message_encoding, schema != nullptr ? schema->encoding : "",
                                          schema != nullptr);
          BagTopic* added = AddTopic(topic);
          if (added->type.empty()) added->type = topic.type;
          if (!topic.problem.empty()) added->problem = topic.problem;
          found = channel_topics.emplace(channel.id, static_cast<int>(added - topics_.data())).first;
        }
        BagTopic& topic = topics_[found->second];
        ++topic.count;
        BagMessage bag_message;
        bag_message.log_time = static_cast<std::int64_t>(message.log_time);
        bag_message.data = message.data;
        bag_message.size = message.size;
        return on_message(topic, bag_message);
      }));
  // Channels without messages are topics too (an empty topic is reported as such).
  for (const auto& [id, channel] : reader.channels()) {
    if (channel_topics.count(id) != 0) continue;
    const auto schema = reader.schemas().find(channel.schema_id);
    BagTopic topic;
    topic.name = channel.topic;
    topic.type = schema != reader.schemas().end() ? schema->second.name : "";
    topic.serialization_format = channel.message_encoding;
    topic.problem = EncodingProblem(channel.message_encoding,
                                    schema != reader.schemas().end() ? schema->second.encoding : "",
                                    schema != reader.schemas().end());
    BagTopic* added = AddTopic(topic);
    if (added->type.empty()) added->type = topic.type;
  }
  return Status::Ok();
}

Status Rosbag2Bag::ReadSqlite(const std::string& file, const MessageCallback& on_message) {
  sqlite3* raw = nullptr;
  const int opened = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  std::unique_ptr<sqlite3, decltype(&sqlite3_close)> db(raw, &sqlite3_close);
  const auto failure = [&](const std::string& what) {
    return Status::Error(file + ": " + what +
                         " (sqlite3: " + (db ? sqlite3_errmsg(db.get()) : "out of memory") + ")");
  };
  if (opened != SQLITE_OK) return failure("cannot open the bag's database");
  const auto prepare = [&](const char* sql, sqlite3_stmt** statement) {
    return sqlite3_prepare_v2(db.get(), sql, -1, statement, nullptr) == SQLITE_OK;
  };
  std::map<std::int64_t, int> topic_ids;  // database id -> index into topics_
  {
    sqlite3_stmt* raw_statement = nullptr;
    if (!prepare("SELECT id, name, type, serialization_format FROM topics", &raw_statement)) {
      sqlite3_finalize(raw_statement);
      return failure("not a rosbag2 sqlite3 database: no topics table");
    }
    std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement(raw_statement, &sqlite3_finalize);
    int step = 0;
    while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
      const auto text = [&](int column) {
        const unsigned char* value = sqlite3_column_text(statement.get(), column);
        return value != nullptr ? std::string(reinterpret_cast<const char*>(value)) : std::string();
      };
      BagTopic topic;
      topic.name = text(1);
      topic.type = text(2);
      topic.serialization_format = text(3);
      if (topic.serialization_format != "cdr") {
        topic.problem = "serialization format '" + topic.serialization_format + "', expected cdr";
      }
      BagTopic* added = AddTopic(topic);
      if (added->type.empty()) added->type = topic.type;
      if (!topic.problem.empty()) added->problem = topic.problem;
      topic_ids[sqlite3_column_int64(statement.get(), 0)] = static_cast<int>(added - topics_.data());
    }
    if (step != SQLITE_DONE) return failure("cannot read the topics table");
  }
  sqlite3_stmt* raw_statement = nullptr;
  if (!prepare("SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id", &raw_statement)) {
    sqlite3_finalize(raw_statement);
    return failure("not a rosbag2 sqlite3 database: no messages table");
  }
  std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement(raw_statement, &sqlite3_finalize);
  int step = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    const std::int64_t topic_id = sqlite3_column_int64(statement.get(), 0);
    const auto found = topic_ids.find(topic_id);
    if (found == topic_ids.end()) {
      return Status::Error(file + ": a message on topic id " + std::to_string(topic_id) +
                           ", which the topics table does not list");
    }
    BagTopic& topic = topics_[found->second];
    ++topic.count;
    BagMessage message;
    message.log_time = sqlite3_column_int64(statement.get(), 1);
    message.data = static_cast<const std::uint8_t*>(sqlite3_column_blob(statement.get(), 2));
    message.size = static_cast<std::size_t>(sqlite3_column_bytes(statement.get(), 2));
    SFM_RETURN_IF_ERROR(on_message(topic, message));
  }
  if (step != SQLITE_DONE) return failure("cannot read the messages table");
  return Status::Ok();
}

}  // namespace sfm

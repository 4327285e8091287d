#include "tests/importers/rosbag2_test_bags.h"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <lz4frame.h>
#include <sqlite3.h>
#include <zlib.h>
#include <zstd.h>

#include <map>

namespace sfm::testing {
namespace {

using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::FastBuffer;

// Little-endian fields of MCAP records.
struct Bytes {
  std::string data;
  void U8(std::uint8_t v) { data.push_back(static_cast<char>(v)); }
  void U16(std::uint16_t v) { Int(v, 2); }
  void U32(std::uint32_t v) { Int(v, 4); }
  void U64(std::uint64_t v) { Int(v, 8); }
  void Int(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) data.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  void Str(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size()));
    data += s;
  }
  void Record(std::uint8_t opcode, const std::string& content) {
    U8(opcode);
    U64(content.size());
    data += content;
  }
};

std::uint32_t Crc(const std::string& bytes) {
  return static_cast<std::uint32_t>(crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

std::string SchemaRecord(std::uint16_t id, const std::string& name, const std::string& encoding) {
  Bytes b;
  b.U16(id);
  b.Str(name);
  b.Str(encoding);
  b.Str("# " + name + " (test schema text)\n");
  return b.data;
}

std::string ChannelRecord(std::uint16_t id, std::uint16_t schema, const std::string& topic,
                          const std::string& encoding) {
  Bytes b;
  b.U16(id);
  b.U16(schema);
  b.Str(topic);
  b.Str(encoding);
  b.U32(0);  // metadata: empty map
  return b.data;
}

std::string Compress(const std::string& records, const std::string& compression) {
  if (compression == "zstd") {
    std::string out(ZSTD_compressBound(records.size()), '\0');
    out.resize(ZSTD_compress(out.data(), out.size(), records.data(), records.size(), 3));
    return out;
  }
  if (compression == "lz4") {
    std::string out(LZ4F_compressFrameBound(records.size(), nullptr), '\0');
    out.resize(LZ4F_compressFrame(out.data(), out.size(), records.data(), records.size(), nullptr));
    return out;
  }
  return records;
}

// A serializer of one message with the ROS 2 encapsulation header.
class Writer {
 public:
  Writer() : cdr_(buffer_, Cdr::LITTLE_ENDIANNESS, Cdr::DDS_CDR) { cdr_.serialize_encapsulation(); }
  Cdr& cdr() { return cdr_; }
  void Header(std::int64_t stamp, const std::string& frame) {
    cdr_.serialize(static_cast<std::int32_t>(stamp / 1000000000));
    cdr_.serialize(static_cast<std::uint32_t>(stamp % 1000000000));
    cdr_.serialize(frame);
  }
  void Pose(const Pose3& pose) {
    const double values[7] = {pose.translation.x(), pose.translation.y(), pose.translation.z(),
                              pose.rotation.x(),    pose.rotation.y(),    pose.rotation.z(),
                              pose.rotation.w()};
    cdr_.serializeArray(values, 7);
  }
  void ByteSequence(const std::vector<std::uint8_t>& bytes) {
    cdr_.serialize(static_cast<std::uint32_t>(bytes.size()));
    if (!bytes.empty()) cdr_.serializeArray(bytes.data(), bytes.size());
  }
  std::vector<std::uint8_t> Done() {
    const char* data = buffer_.getBuffer();
    return std::vector<std::uint8_t>(data, data + cdr_.getSerializedDataLength());
  }

 private:
  FastBuffer buffer_;
  Cdr cdr_;
};

}  // namespace

std::string WriteMcap(const std::vector<BagMessageSpec>& messages, const McapWriteOptions& options) {
  // Schemas and channels in order of first use, each defined before its first message.
  std::map<std::string, std::uint16_t> schema_ids, channel_ids;
  std::map<std::uint16_t, std::uint64_t> counts;
  std::vector<std::string> records, definitions;
  const auto define = [&](const std::string& topic, const std::string& type, std::vector<std::string>* out) {
    if (schema_ids.count(type) == 0) {
      const std::uint16_t id = static_cast<std::uint16_t>(schema_ids.size() + 1);
      schema_ids[type] = id;
      Bytes b;
      b.Record(0x03, SchemaRecord(id, type, options.schema_encoding));
      out->push_back(b.data);
      definitions.push_back(b.data);
    }
    if (channel_ids.count(topic) == 0) {
      const std::uint16_t id = static_cast<std::uint16_t>(channel_ids.size());
      channel_ids[topic] = id;
      counts[id] = 0;
      Bytes b;
      b.Record(0x04, ChannelRecord(id, schema_ids[type], topic, options.message_encoding));
      out->push_back(b.data);
      definitions.push_back(b.data);
    }
    return channel_ids[topic];
  };
  for (const std::string& topic_type : options.empty_topics) {
    const size_t space = topic_type.find(' ');
    define(topic_type.substr(0, space), topic_type.substr(space + 1), &records);
  }
  for (size_t i = 0; i < messages.size(); ++i) {
    const BagMessageSpec& m = messages[i];
    const std::uint16_t channel = define(m.topic, m.type, &records);
    ++counts[channel];
    Bytes content;
    content.U16(channel);
    content.U32(static_cast<std::uint32_t>(i));
    content.U64(static_cast<std::uint64_t>(m.log_time));
    content.U64(static_cast<std::uint64_t>(m.log_time));
    content.data.append(reinterpret_cast<const char*>(m.data.data()), m.data.size());
    Bytes b;
    b.Record(0x05, content.data);
    records.push_back(b.data);
  }

  Bytes file;
  file.data = std::string("\x89MCAP0\r\n", 8);
  Bytes header;
  header.Str("ros2");
  header.Str("junction-sfm test writer");
  file.Record(0x01, header.data);
  std::uint32_t chunk_count = 0;
  if (options.chunked) {
    std::string chunk;
    const auto flush = [&] {
      if (chunk.empty()) return;
      Bytes c;
      c.U64(0);
      c.U64(0);
      c.U64(chunk.size());
      c.U32(Crc(chunk));
      c.Str(options.compression);
      const std::string compressed = Compress(chunk, options.compression);
      c.U64(compressed.size());
      c.data += compressed;
      file.Record(0x06, c.data);
      chunk.clear();
      ++chunk_count;
    };
    for (const std::string& record : records) {
      chunk += record;
      if (chunk.size() >= options.chunk_bytes) flush();
    }
    flush();
  } else {
    for (const std::string& record : records) file.data += record;
  }
  Bytes data_end;
  data_end.U32(Crc(file.data));
  file.Record(0x0F, data_end.data);

  std::uint64_t summary_start = 0;
  if (options.summary) {
    summary_start = file.data.size();
    for (const std::string& definition : definitions) file.data += definition;
    Bytes statistics;
    statistics.U64(messages.size());
    statistics.U16(static_cast<std::uint16_t>(schema_ids.size()));
    statistics.U32(static_cast<std::uint32_t>(channel_ids.size()));
    statistics.U32(0);
    statistics.U32(0);
    statistics.U32(chunk_count);
    statistics.U64(messages.empty() ? 0 : messages.front().log_time);
    statistics.U64(messages.empty() ? 0 : messages.back().log_time);
    statistics.U32(static_cast<std::uint32_t>(counts.size() * 10));
    for (const auto& [channel, count] : counts) {
      statistics.U16(channel);
      statistics.U64(count);
    }
    file.Record(0x0B, statistics.data);
  }
  const size_t footer_start = file.data.size();
  file.U8(0x02);
  file.U64(20);
  file.U64(summary_start);
  file.U64(0);
  file.U32(options.summary ? Crc(file.data.substr(summary_start)) : 0);
  (void)footer_start;
  file.data += std::string("\x89MCAP0\r\n", 8);
  return file.data;
}

bool WriteSqliteBag(const std::string& path, const std::vector<BagMessageSpec>& messages) {
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) return false;
  bool ok =
      sqlite3_exec(db,
                   "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
                   "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
                   "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
                   "timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
                   nullptr, nullptr, nullptr) == SQLITE_OK;
  std::map<std::string, int> ids;
  for (const BagMessageSpec& m : messages) {
    if (ids.count(m.topic) != 0) continue;
    const int id = static_cast<int>(ids.size()) + 1;
    ids[m.topic] = id;
    const std::string sql = "INSERT INTO topics VALUES(" + std::to_string(id) + ", '" + m.topic + "', '" +
                            m.type + "', 'cdr', '');";
    ok = ok && sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
  }
  sqlite3_stmt* insert = nullptr;
  ok = ok && sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1,
                                &insert, nullptr) == SQLITE_OK;
  for (const BagMessageSpec& m : messages) {
    if (!ok) break;
    sqlite3_bind_int(insert, 1, ids[m.topic]);
    sqlite3_bind_int64(insert, 2, m.log_time);
    sqlite3_bind_blob(insert, 3, m.data.data(), static_cast<int>(m.data.size()), SQLITE_TRANSIENT);
    ok = sqlite3_step(insert) == SQLITE_DONE;
    sqlite3_reset(insert);
  }
  sqlite3_finalize(insert);
  sqlite3_close(db);
  return ok;
}

std::string Rosbag2Metadata(const std::string& storage, const std::string& file,
                            const std::vector<BagMessageSpec>& messages) {
  std::map<std::string, std::pair<std::string, int>> topics;
  for (const BagMessageSpec& m : messages) {
    topics[m.topic].first = m.type;
    ++topics[m.topic].second;
  }
  std::string text = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: " + storage +
                     "\n  relative_file_paths:\n    - " + file +
                     "\n  message_count: " + std::to_string(messages.size()) +
                     "\n  topics_with_message_count:\n";
  for (const auto& [name, type_count] : topics) {
    text += "    - topic_metadata:\n        name: " + name + "\n        type: " + type_count.first +
            "\n        serialization_format: cdr\n        offered_qos_profiles: \"\"\n      message_count: " +
            std::to_string(type_count.second) + "\n";
  }
  text += "  compression_format: \"\"\n  compression_mode: \"\"\n";
  return text;
}

std::vector<std::uint8_t> CdrImage(std::int64_t stamp, const std::string& frame, int width, int height,
                                   const std::string& encoding, std::uint32_t step,
                                   const std::vector<std::uint8_t>& pixels) {
  Writer w;
  w.Header(stamp, frame);
  w.cdr().serialize(static_cast<std::uint32_t>(height));
  w.cdr().serialize(static_cast<std::uint32_t>(width));
  w.cdr().serialize(encoding);
  w.cdr().serialize(static_cast<std::uint8_t>(0));
  w.cdr().serialize(step);
  w.ByteSequence(pixels);
  return w.Done();
}

std::vector<std::uint8_t> CdrCompressedImage(std::int64_t stamp, const std::string& frame,
                                             const std::string& format,
                                             const std::vector<std::uint8_t>& bytes) {
  Writer w;
  w.Header(stamp, frame);
  w.cdr().serialize(format);
  w.ByteSequence(bytes);
  return w.Done();
}

std::vector<std::uint8_t> CdrOdometry(std::int64_t stamp, const std::string& frame, const std::string& child,
                                      const Pose3& pose) {
  Writer w;
  w.Header(stamp, frame);
  w.cdr().serialize(child);
  w.Pose(pose);
  const double covariance[36] = {};
  w.cdr().serializeArray(covariance, 36);
  const double twist[6] = {0.1, 0, 0, 0, 0, 0.01};
  w.cdr().serializeArray(twist, 6);
  w.cdr().serializeArray(covariance, 36);
  return w.Done();
}

std::vector<std::uint8_t> CdrPoseStamped(std::int64_t stamp, const std::string& frame, const Pose3& pose) {
  Writer w;
  w.Header(stamp, frame);
  w.Pose(pose);
  return w.Done();
}

std::vector<std::uint8_t> CdrTfMessage(const std::vector<std::pair<std::string, std::string>>& parent_child,
                                       const std::vector<Pose3>& parent_T_child) {
  Writer w;
  w.cdr().serialize(static_cast<std::uint32_t>(parent_child.size()));
  for (size_t i = 0; i < parent_child.size(); ++i) {
    w.Header(0, parent_child[i].first);
    w.cdr().serialize(parent_child[i].second);
    w.Pose(parent_T_child[i]);
  }
  return w.Done();
}

std::vector<std::uint8_t> CdrCameraInfo(std::int64_t stamp, const std::string& frame, int width, int height,
                                        const std::string& model, const std::vector<double>& d, double fx,
                                        double fy, double cx, double cy) {
  Writer w;
  w.Header(stamp, frame);
  w.cdr().serialize(static_cast<std::uint32_t>(height));
  w.cdr().serialize(static_cast<std::uint32_t>(width));
  w.cdr().serialize(model);
  w.cdr().serialize(static_cast<std::uint32_t>(d.size()));
  if (!d.empty()) w.cdr().serializeArray(d.data(), d.size());
  const double k[9] = {fx, 0, cx, 0, fy, cy, 0, 0, 1};
  const double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double p[12] = {fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0};
  w.cdr().serializeArray(k, 9);
  w.cdr().serializeArray(r, 9);
  w.cdr().serializeArray(p, 12);
  w.cdr().serialize(static_cast<std::uint32_t>(0));                              // binning_x
  w.cdr().serialize(static_cast<std::uint32_t>(0));                              // binning_y
  for (int i = 0; i < 4; ++i) w.cdr().serialize(static_cast<std::uint32_t>(0));  // roi offsets and size
  w.cdr().serialize(static_cast<std::uint8_t>(0));                               // roi.do_rectify
  return w.Done();
}

}  // namespace sfm::testing

#include "sequences/importers/rosbag/mcap_reader.h"

#include <glog/logging.h>
#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <cstring>
#include <filesystem>
#include <memory>

namespace sfm {
namespace {

// Record opcodes (MCAP specification, "Records").
constexpr std::uint8_t kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05,
                       kChunk = 0x06, kStatistics = 0x0B, kDataEnd = 0x0F;
constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint64_t kRecordPrefix = 9;    // opcode (1) and content length (8)
constexpr std::uint64_t kFooterContent = 20;  // summary_start, summary_offset_start, summary_crc
// A chunk stating more than this uncompressed is taken as corrupt rather than allocated.
constexpr std::uint64_t kMaxChunkSize = std::uint64_t{1} << 32;

std::uint32_t Crc32(std::uint32_t crc, const std::uint8_t* data, std::size_t size) {
  return static_cast<std::uint32_t>(crc32_z(crc, data, size));
}

// Little-endian fields of a record's content, as the specification lays them out: integers,
// strings and byte arrays with a uint32 length prefix, maps with a uint32 byte-length prefix.
class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::uint64_t size) : data_(data), size_(size) {}

  template <typename T>
  bool Int(T* value) {
    if (size_ - position_ < sizeof(T)) return false;
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v |= std::uint64_t{data_[position_ + i]} << (8 * i);
    *value = static_cast<T>(v);
    position_ += sizeof(T);
    return true;
  }
  bool Bytes(std::uint64_t count, const std::uint8_t** bytes) {
    if (size_ - position_ < count) return false;
    *bytes = data_ + position_;
    position_ += count;
    return true;
  }
  bool String(std::string* text) {
    std::uint32_t length = 0;
    const std::uint8_t* bytes = nullptr;
    if (!Int(&length) || !Bytes(length, &bytes)) return false;
    text->assign(reinterpret_cast<const char*>(bytes), length);
    return true;
  }
  bool StringMap(std::map<std::string, std::string>* map) {
    std::uint32_t length = 0;
    const std::uint8_t* bytes = nullptr;
    if (!Int(&length) || !Bytes(length, &bytes)) return false;
    Cursor entries(bytes, length);
    while (entries.remaining() > 0) {
      std::string key, value;
      if (!entries.String(&key) || !entries.String(&value)) return false;
      (*map)[key] = value;
    }
    return true;
  }
  std::uint64_t remaining() const { return size_ - position_; }
  const std::uint8_t* here() const { return data_ + position_; }

 private:
  const std::uint8_t* data_;
  std::uint64_t size_;
  std::uint64_t position_ = 0;
};

bool ParseSchema(const std::uint8_t* content, std::uint64_t length, McapSchema* schema) {
  Cursor cursor(content, length);
  std::uint32_t data_length = 0;
  const std::uint8_t* data = nullptr;
  if (!cursor.Int(&schema->id) || !cursor.String(&schema->name) || !cursor.String(&schema->encoding) ||
      !cursor.Int(&data_length) || !cursor.Bytes(data_length, &data)) {
    return false;
  }
  schema->data.assign(reinterpret_cast<const char*>(data), data_length);
  return true;
}

bool ParseChannel(const std::uint8_t* content, std::uint64_t length, McapChannel* channel) {
  Cursor cursor(content, length);
  return cursor.Int(&channel->id) && cursor.Int(&channel->schema_id) && cursor.String(&channel->topic) &&
         cursor.String(&channel->message_encoding) && cursor.StringMap(&channel->metadata);
}

// Reads exactly `size` bytes at the stream's position; false at the end of the file.
bool ReadExactly(std::ifstream& in, std::uint8_t* data, std::uint64_t size) {
  in.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(size));
  return static_cast<std::uint64_t>(in.gcount()) == size;
}

std::uint64_t LittleEndian64(const std::uint8_t* bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value |= std::uint64_t{bytes[i]} << (8 * i);
  return value;
}

}  // namespace

Status McapReader::Error(std::uint64_t offset, const std::string& problem) const {
  return Status::Error(path_ + ": byte " + std::to_string(offset) + ": " + problem);
}

Status McapReader::Open(const std::string& path) {
  path_ = path;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return Status::Error(path + ": file does not exist");
  file_size_ = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (!in || error) return Status::Error(path + ": cannot be read");
  std::uint8_t magic[8];
  if (!ReadExactly(in, magic, 8) || std::memcmp(magic, kMagic, 5) != 0) {
    return Status::Error(path + ": not an MCAP file (no MCAP magic at its start)");
  }
  if (magic[5] != '0' || magic[6] != '\r' || magic[7] != '\n') {
    return Status::Error(path + ": unsupported MCAP major version '" +
                         std::string(1, static_cast<char>(magic[5])) + "' (this reader knows version 0)");
  }
  std::uint8_t prefix[kRecordPrefix];
  if (!ReadExactly(in, prefix, kRecordPrefix) || prefix[0] != kHeader) {
    return Error(8, "the file does not start with a Header record");
  }
  const std::uint64_t header_length = LittleEndian64(prefix + 1);
  if (header_length > file_size_ - 8 - kRecordPrefix) return Error(8, "truncated Header record");
  std::vector<std::uint8_t> header(header_length);
  if (!ReadExactly(in, header.data(), header_length)) return Error(8, "truncated Header record");
  Cursor cursor(header.data(), header_length);
  std::string library;
  if (!cursor.String(&profile_) || !cursor.String(&library)) return Error(8, "malformed Header record");

  // The footer: the record just before the closing magic. A file without one was not closed
  // (a recording cut short); its data section runs to the end of the file.
  data_end_ = file_size_;
  const std::uint64_t footer_size = kRecordPrefix + kFooterContent;
  std::uint8_t tail[footer_size + 8];
  if (file_size_ < 8 + kRecordPrefix + header_length + footer_size + 8) {
    LOG(WARNING) << path << ": no footer (the file was not closed); reading its data section to the end";
    return Status::Ok();
  }
  const std::uint64_t footer_offset = file_size_ - 8 - footer_size;
  in.seekg(static_cast<std::streamoff>(footer_offset));
  if (!ReadExactly(in, tail, sizeof(tail))) return Status::Error(path + ": cannot be read");
  if (std::memcmp(tail + footer_size, kMagic, 8) != 0) {
    LOG(WARNING) << path
                 << ": no closing magic (the file was not closed); reading its data section to the end";
    return Status::Ok();
  }
  if (tail[0] != kFooter || LittleEndian64(tail + 1) != kFooterContent) {
    return Error(footer_offset, "malformed Footer record before the closing magic");
  }
  Cursor footer(tail + kRecordPrefix, kFooterContent);
  std::uint64_t summary_start = 0, summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
  (void)(footer.Int(&summary_start) && footer.Int(&summary_offset_start) && footer.Int(&summary_crc));
  data_end_ = footer_offset;
  if (summary_start == 0) return Status::Ok();
  if (summary_start > footer_offset || summary_offset_start > footer_offset ||
      (summary_offset_start != 0 && summary_offset_start < summary_start)) {
    return Error(footer_offset, "the footer's summary offsets lie outside the file");
  }
  data_end_ = summary_start;
  return ReadSummary(summary_start, footer_offset, summary_crc);
}

Status McapReader::ReadSummary(std::uint64_t summary_start, std::uint64_t footer_offset,
                               std::uint32_t summary_crc) {
  // The summary CRC covers the summary and summary offset sections and the footer up to (not
  // including) its summary_crc field.
  const std::uint64_t crc_end = footer_offset + kRecordPrefix + 16;
  std::vector<std::uint8_t> bytes(crc_end - summary_start);
  std::ifstream in(path_, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(summary_start));
  if (!ReadExactly(in, bytes.data(), bytes.size())) return Status::Error(path_ + ": cannot be read");
  if (summary_crc != 0 && Crc32(0, bytes.data(), bytes.size()) != summary_crc) {
    return Error(summary_start, "summary section CRC mismatch (the file is corrupt)");
  }
  summary_.present = true;
  Cursor records(bytes.data(), footer_offset - summary_start);
  while (records.remaining() > 0) {
    const std::uint64_t offset = summary_start + (records.here() - bytes.data());
    std::uint8_t opcode = 0;
    std::uint64_t length = 0;
    const std::uint8_t* content = nullptr;
    if (!records.Int(&opcode) || !records.Int(&length) || !records.Bytes(length, &content)) {
      return Error(offset, "truncated record in the summary section");
    }
    if (opcode == kSchema) {
      McapSchema schema;
      if (!ParseSchema(content, length, &schema)) return Error(offset, "malformed Schema record");
      summary_.schemas[schema.id] = schema;
    } else if (opcode == kChannel) {
      McapChannel channel;
      if (!ParseChannel(content, length, &channel)) return Error(offset, "malformed Channel record");
      summary_.channels[channel.id] = channel;
    } else if (opcode == kStatistics) {
      Cursor statistics(content, length);
      std::uint16_t schema_count = 0;
      std::uint32_t channel_count = 0, attachment_count = 0, metadata_count = 0, counts_length = 0;
      std::uint64_t start_time = 0, end_time = 0;
      const std::uint8_t* counts = nullptr;
      if (!statistics.Int(&summary_.message_count) || !statistics.Int(&schema_count) ||
          !statistics.Int(&channel_count) || !statistics.Int(&attachment_count) ||
          !statistics.Int(&metadata_count) || !statistics.Int(&summary_.chunk_count) ||
          !statistics.Int(&start_time) || !statistics.Int(&end_time) || !statistics.Int(&counts_length) ||
          !statistics.Bytes(counts_length, &counts) || counts_length % 10 != 0) {
        return Error(offset, "malformed Statistics record");
      }
      Cursor entries(counts, counts_length);
      for (std::uint32_t i = 0; i < counts_length / 10; ++i) {
        std::uint16_t channel = 0;
        std::uint64_t count = 0;
        (void)(entries.Int(&channel) && entries.Int(&count));
        summary_.channel_message_counts[channel] = count;
      }
      summary_.has_statistics = true;
    }
  }
  return Status::Ok();
}

Status McapReader::HandleRecord(std::uint8_t opcode, const std::uint8_t* content, std::uint64_t length,
                                std::uint64_t offset, bool in_chunk, const MessageCallback& on_message) {
  switch (opcode) {
    case kSchema: {
      McapSchema schema;
      if (!ParseSchema(content, length, &schema)) return Error(offset, "malformed Schema record");
      schemas_[schema.id] = schema;
      return Status::Ok();
    }
    case kChannel: {
      McapChannel channel;
      if (!ParseChannel(content, length, &channel)) return Error(offset, "malformed Channel record");
      channels_[channel.id] = channel;
      return Status::Ok();
    }
    case kMessage: {
      Cursor cursor(content, length);
      McapMessage message;
      if (!cursor.Int(&message.channel_id) || !cursor.Int(&message.sequence) ||
          !cursor.Int(&message.log_time) || !cursor.Int(&message.publish_time)) {
        return Error(offset, "malformed Message record");
      }
      message.data = cursor.here();
      message.size = cursor.remaining();
      const auto channel = channels_.find(message.channel_id);
      if (channel == channels_.end()) {
        return Error(offset, "message on channel " + std::to_string(message.channel_id) +
                                 ", which no Channel record defines before it");
      }
      const McapSchema* schema = nullptr;
      if (channel->second.schema_id != 0) {
        const auto found = schemas_.find(channel->second.schema_id);
        if (found == schemas_.end()) {
          return Error(offset, "channel " + channel->second.topic + " refers to schema " +
                                   std::to_string(channel->second.schema_id) +
                                   ", which no Schema record defines");
        }
        schema = &found->second;
      }
      return on_message(channel->second, schema, message);
    }
    case kChunk:
      if (in_chunk) return Error(offset, "a Chunk record inside a chunk");
      return ReadChunk(content, length, offset, on_message);
    default:
      // Indexes, attachments, metadata and records of later minor versions carry no messages.
      return Status::Ok();
  }
}

Status McapReader::ReadChunk(const std::uint8_t* content, std::uint64_t length, std::uint64_t offset,
                             const MessageCallback& on_message) {
  Cursor cursor(content, length);
  std::uint64_t start_time = 0, end_time = 0, uncompressed_size = 0, records_length = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;
  const std::uint8_t* records = nullptr;
  if (!cursor.Int(&start_time) || !cursor.Int(&end_time) || !cursor.Int(&uncompressed_size) ||
      !cursor.Int(&uncompressed_crc) || !cursor.String(&compression) || !cursor.Int(&records_length)) {
    return Error(offset, "malformed Chunk record");
  }
  if (!cursor.Bytes(records_length, &records))
    return Error(offset, "truncated chunk (its records run past the record)");
  if (uncompressed_size > kMaxChunkSize) {
    return Error(offset,
                 "chunk states " + std::to_string(uncompressed_size) + " bytes uncompressed (corrupt)");
  }
  const std::uint8_t* data = records;
  if (compression.empty()) {
    if (records_length != uncompressed_size) {
      return Error(offset, "uncompressed chunk of " + std::to_string(records_length) + " bytes states " +
                               std::to_string(uncompressed_size));
    }
  } else if (compression == "zstd") {
    decompressed_.resize(uncompressed_size);
    const std::size_t size =
        ZSTD_decompress(decompressed_.data(), decompressed_.size(), records, records_length);
    if (ZSTD_isError(size)) {
      return Error(offset, std::string("zstd chunk does not decompress (") + ZSTD_getErrorName(size) + ")");
    }
    if (size != uncompressed_size) {
      return Error(offset, "zstd chunk decompresses to " + std::to_string(size) + " bytes, states " +
                               std::to_string(uncompressed_size));
    }
    data = decompressed_.data();
  } else if (compression == "lz4") {
    // MCAP's lz4 chunks are LZ4 frames (the frame format, not raw blocks).
    decompressed_.resize(uncompressed_size);
    LZ4F_dctx* context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
      return Error(offset, "cannot create an lz4 decompression context");
    }
    std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> owner(
        context, &LZ4F_freeDecompressionContext);
    std::size_t produced = 0, consumed = 0, hint = 1;
    while (hint != 0) {
      std::size_t out_size = decompressed_.size() - produced, in_size = records_length - consumed;
      hint = LZ4F_decompress(context, decompressed_.data() + produced, &out_size, records + consumed,
                             &in_size, nullptr);
      if (LZ4F_isError(hint)) {
        return Error(offset, std::string("lz4 chunk does not decompress (") + LZ4F_getErrorName(hint) + ")");
      }
      produced += out_size;
      consumed += in_size;
      if (hint != 0 && out_size == 0 && in_size == 0) {
        return Error(offset, "lz4 chunk ends early or decompresses to more than its stated " +
                                 std::to_string(uncompressed_size) + " bytes");
      }
    }
    if (produced != uncompressed_size) {
      return Error(offset, "lz4 chunk decompresses to " + std::to_string(produced) + " bytes, states " +
                               std::to_string(uncompressed_size));
    }
    data = decompressed_.data();
  } else {
    return Error(offset,
                 "unknown chunk compression '" + compression + "' (this reader knows zstd, lz4 and none)");
  }
  if (uncompressed_crc != 0 && Crc32(0, data, uncompressed_size) != uncompressed_crc) {
    return Error(offset, "chunk CRC mismatch (the chunk is corrupt)");
  }
  // The callback reads the messages' bytes during the call only: the next chunk reuses the buffer.
  const std::uint8_t* bytes = data;
  Cursor inner(bytes, uncompressed_size);
  while (inner.remaining() > 0) {
    const std::uint64_t inner_offset = inner.here() - bytes;
    std::uint8_t opcode = 0;
    std::uint64_t inner_length = 0;
    const std::uint8_t* inner_content = nullptr;
    if (!inner.Int(&opcode) || !inner.Int(&inner_length) || !inner.Bytes(inner_length, &inner_content)) {
      return Error(offset,
                   "truncated record at byte " + std::to_string(inner_offset) + " of the chunk's records");
    }
    SFM_RETURN_IF_ERROR(HandleRecord(opcode, inner_content, inner_length, offset, true, on_message));
  }
  return Status::Ok();
}

Status McapReader::ReadMessages(const MessageCallback& on_message) {
  channels_.clear();
  schemas_.clear();
  std::ifstream in(path_, std::ios::binary);
  if (!in) return Status::Error(path_ + ": cannot be read");
  std::vector<std::uint8_t> content;
  std::uint8_t magic[8];
  if (!ReadExactly(in, magic, 8)) return Status::Error(path_ + ": cannot be read");
  std::uint32_t crc = Crc32(0, magic, 8);
  std::uint64_t offset = 8;
  while (offset < data_end_) {
    std::uint8_t prefix[kRecordPrefix];
    if (data_end_ - offset < kRecordPrefix || !ReadExactly(in, prefix, kRecordPrefix)) {
      return Error(offset, "truncated record (the file ends inside it)");
    }
    const std::uint8_t opcode = prefix[0];
    const std::uint64_t length = LittleEndian64(prefix + 1);
    if (length > data_end_ - offset - kRecordPrefix) {
      return Error(offset, std::string(opcode == kChunk ? "truncated chunk" : "truncated record") +
                               ": it states " + std::to_string(length) + " bytes, the data section has " +
                               std::to_string(data_end_ - offset - kRecordPrefix) + " left");
    }
    content.resize(length);
    if (!ReadExactly(in, content.data(), length)) return Error(offset, "cannot read the record");
    if (opcode == kDataEnd) {
      Cursor cursor(content.data(), length);
      std::uint32_t data_crc = 0;
      if (!cursor.Int(&data_crc)) return Error(offset, "malformed DataEnd record");
      if (data_crc != 0 && data_crc != crc)
        return Error(offset, "data section CRC mismatch (the file is corrupt)");
      return Status::Ok();
    }
    crc = Crc32(crc, prefix, kRecordPrefix);
    crc = Crc32(crc, content.data(), length);
    if (opcode == kHeader || opcode == kFooter) {
      if (opcode == kFooter || offset != 8)
        return Error(offset, "unexpected Header or Footer record in the data section");
    } else {
      SFM_RETURN_IF_ERROR(HandleRecord(opcode, content.data(), length, offset, false, on_message));
    }
    offset += kRecordPrefix + length;
  }
  if (summary_.present) return Error(offset, "the data section ends without a DataEnd record");
  return Status::Ok();
}

}  // namespace sfm

// ROS 2 bags: the MCAP and sqlite3 readers on bags rosbag2 itself recorded, corrupt files, and
// import_sequence --format rosbag2 on bags written from a generated sequence (round trips, the
// keyframe and window options, bad input).
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "frontend/sequence/sequence.h"
#include "sequences/importers/rosbag/mcap_reader.h"
#include "sequences/importers/rosbag/ros2_messages.h"
#include "sequences/importers/rosbag/rosbag2_bag.h"
#include "tests/importers/bag_test_support.h"
#include "tests/importers/rosbag2_test_bags.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using testing::BagMessageSpec;
using ::testing::HasSubstr;
using testing::McapWriteOptions;

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::string ReadBytes(const fs::path& path) { return sfm::testing::ReadFile(path.string()); }

// --- Bags recorded by rosbag2 (../shared/data/rosbag2-test-bags) -----------------------------

struct Counted {
  std::map<std::string, std::uint64_t> counts;
  std::map<std::string, std::string> types;
  std::map<std::string, std::vector<std::vector<std::uint8_t>>> payloads;
};

Status ReadAll(const std::string& path, Counted* counted, std::string* storage) {
  Rosbag2Bag bag;
  SFM_RETURN_IF_ERROR(bag.Open(path));
  *storage = bag.storage();
  SFM_RETURN_IF_ERROR(bag.ReadMessages([&](const BagTopic& topic, const BagMessage& message) {
    counted->payloads[topic.name].emplace_back(message.data, message.data + message.size);
    return Status::Ok();
  }));
  for (const BagTopic& topic : bag.topics()) {
    counted->counts[topic.name] = topic.count;
    counted->types[topic.name] = topic.type;
    EXPECT_EQ(topic.problem, "") << topic.name;
  }
  return Status::Ok();
}

class RealBags : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = sfm::testing::SharedDataDir("rosbag2-test-bags");
    if (dir_.empty())
      GTEST_SKIP() << "../shared/data/rosbag2-test-bags is absent: real rosbag2 bags not tested";
  }
  std::string dir_;
};

// Topics, types and message counts exactly as rosbag2's metadata.yaml states them, in all four
// bags (MCAP: one chunk uncompressed, one zstd-compressed with its CRC; sqlite3).
TEST_F(RealBags, TopicsTypesAndCountsOfAllFourBags) {
  for (const std::string name : {"mcap-cdr_test", "sqlite3-cdr_test"}) {
    Counted counted;
    std::string storage;
    ASSERT_TRUE(ReadAll(dir_ + "/" + name, &counted, &storage).ok()) << name;
    EXPECT_EQ(storage, name.substr(0, name.find('-')));
    EXPECT_EQ(counted.counts["/array_topic"], 4u) << name;
    EXPECT_EQ(counted.counts["/test_topic"], 3u) << name;
    EXPECT_EQ(counted.types["/array_topic"], "test_msgs/msg/Arrays") << name;
    EXPECT_EQ(counted.types["/test_topic"], "test_msgs/msg/BasicTypes") << name;
  }
  for (const std::string name : {"mcap-talker", "sqlite3-talker"}) {
    Counted counted;
    std::string storage;
    ASSERT_TRUE(ReadAll(dir_ + "/" + name, &counted, &storage).ok()) << name;
    EXPECT_EQ(counted.counts["/topic"], 10u) << name;
    EXPECT_EQ(counted.counts["/rosout"], 10u) << name;
    EXPECT_EQ(counted.counts["/parameter_events"], 0u) << name;
    EXPECT_EQ(counted.types["/topic"], "std_msgs/msg/String") << name;
    EXPECT_EQ(counted.types["/rosout"], "rcl_interfaces/msg/Log") << name;
  }
}

// The same recording in both storages: byte-identical CDR payloads in the same order.
TEST_F(RealBags, McapAndSqliteHoldTheSameMessages) {
  for (const std::string name : {"cdr_test", "talker"}) {
    Counted mcap, sqlite;
    std::string storage;
    ASSERT_TRUE(ReadAll(dir_ + "/mcap-" + name, &mcap, &storage).ok());
    ASSERT_TRUE(ReadAll(dir_ + "/sqlite3-" + name, &sqlite, &storage).ok());
    for (const auto& [topic, payloads] : sqlite.payloads) {
      EXPECT_EQ(mcap.payloads[topic], payloads) << name << " " << topic;
    }
  }
}

// The MCAP summary (CRC checked on opening) agrees with the scan: schemas, channels, counts.
TEST_F(RealBags, McapSummaryAgreesWithTheDataSection) {
  for (const std::string file : {"mcap-cdr_test/cdr_test_0.mcap", "mcap-talker/talker.mcap"}) {
    McapReader reader;
    ASSERT_TRUE(reader.Open(dir_ + "/" + file).ok()) << file;
    EXPECT_EQ(reader.profile(), "ros2");
    ASSERT_TRUE(reader.summary().present);
    ASSERT_TRUE(reader.summary().has_statistics);
    std::map<std::uint16_t, std::uint64_t> counts;
    ASSERT_TRUE(
        reader
            .ReadMessages([&](const McapChannel& channel, const McapSchema* schema, const McapMessage&) {
              EXPECT_NE(schema, nullptr);
              if (schema != nullptr) {
                EXPECT_EQ(schema->encoding, "ros2msg");
              }
              EXPECT_EQ(channel.message_encoding, "cdr");
              ++counts[channel.id];
              return Status::Ok();
            })
            .ok());
    std::uint64_t total = 0;
    for (const auto& [channel, count] : counts) {
      EXPECT_EQ(reader.summary().channel_message_counts.at(channel), count) << file << " channel " << channel;
      total += count;
    }
    EXPECT_EQ(reader.summary().message_count, total);
    EXPECT_EQ(reader.summary().channels.size(), reader.channels().size());
    for (const auto& [id, schema] : reader.summary().schemas)
      EXPECT_EQ(reader.schemas().at(id).name, schema.name);
  }
}

// std_msgs/String of the talker decodes to "Hello, world! N" (Fast CDR on rosbag2's bytes).
TEST_F(RealBags, TalkerStringsDecode) {
  for (const std::string name : {"mcap-talker", "sqlite3-talker"}) {
    Counted counted;
    std::string storage;
    ASSERT_TRUE(ReadAll(dir_ + "/" + name, &counted, &storage).ok());
    ASSERT_EQ(counted.payloads["/topic"].size(), 10u);
    for (size_t i = 0; i < 10; ++i) {
      std::vector<std::uint8_t>& bytes = counted.payloads["/topic"][i];
      eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(bytes.data()), bytes.size());
      eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                                 eprosima::fastcdr::Cdr::DDS_CDR);
      cdr.read_encapsulation();
      std::string text;
      cdr.deserialize(text);
      EXPECT_EQ(text, "Hello, world! " + std::to_string(i)) << name;
    }
  }
}

// test_msgs/BasicTypes: the 13 fields in their .msg order consume the whole message (CDR
// alignment right), in both storages.
TEST_F(RealBags, BasicTypesDecodeToTheirLength) {
  for (const std::string name : {"mcap-cdr_test", "sqlite3-cdr_test"}) {
    Counted counted;
    std::string storage;
    ASSERT_TRUE(ReadAll(dir_ + "/" + name, &counted, &storage).ok());
    for (std::vector<std::uint8_t>& bytes : counted.payloads["/test_topic"]) {
      eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(bytes.data()), bytes.size());
      eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN,
                                 eprosima::fastcdr::Cdr::DDS_CDR);
      cdr.read_encapsulation();
      bool b;
      std::uint8_t byte, u8;
      char c;
      float f32;
      double f64;
      std::int8_t i8;
      std::int16_t i16;
      std::uint16_t u16;
      std::int32_t i32;
      std::uint32_t u32;
      std::int64_t i64;
      std::uint64_t u64;
      cdr >> b >> byte >> c >> f32 >> f64 >> i8 >> u8 >> i16 >> u16 >> i32 >> u32 >> i64 >> u64;
      EXPECT_EQ(cdr.getSerializedDataLength(), bytes.size()) << name;
      EXPECT_TRUE(std::isfinite(f32) && std::isfinite(f64));
    }
  }
}

// Corrupt copies of rosbag2's zstd-compressed MCAP: each is refused with the file and the problem.
TEST_F(RealBags, CorruptMcapFilesAreRefused) {
  const std::string original = ReadBytes(dir_ + "/mcap-talker/talker.mcap");
  const fs::path scratch = sfm::testing::MakeScratchDir("rosbag2_corrupt");
  // The chunk record is the second record: magic (8), Header (9 + 28), then the chunk.
  const size_t chunk = 8 + 9 + 28;
  ASSERT_EQ(static_cast<std::uint8_t>(original[chunk]), 0x06);
  const size_t compression = chunk + 9 + 8 + 8 + 8 + 4 + 4;  // the compression string's bytes
  ASSERT_EQ(original.substr(compression, 4), "zstd");
  struct Case {
    std::string name, bytes, expected;
  };
  std::vector<Case> cases;
  cases.push_back({"truncated", original.substr(0, chunk + 1500), "truncated chunk"});
  std::string unknown = original;
  unknown.replace(compression, 4, "brot");
  cases.push_back({"unknown_compression", unknown, "unknown chunk compression 'brot'"});
  std::string flipped = original;
  flipped[chunk + 1000] = static_cast<char>(flipped[chunk + 1000] ^ 0x20);
  cases.push_back({"flipped", flipped, "chunk"});
  std::string summary = original;
  summary[original.size() - 200] = static_cast<char>(summary[original.size() - 200] ^ 0x01);
  cases.push_back({"summary", summary, "summary section CRC mismatch"});
  for (const Case& c : cases) {
    const fs::path path = scratch / (c.name + ".mcap");
    WriteBytes(path, c.bytes);
    Rosbag2Bag bag;
    Status status = bag.Open(path.string());
    if (status.ok())
      status = bag.ReadMessages([](const BagTopic&, const BagMessage&) { return Status::Ok(); });
    ASSERT_FALSE(status.ok()) << c.name;
    EXPECT_THAT(status.message(), HasSubstr(path.string())) << c.name;
    EXPECT_THAT(status.message(), HasSubstr(c.expected)) << c.name;
  }
}

// Every single-byte corruption of rosbag2's zstd MCAP file (one position in 13) is either read or
// refused with the file's name: never a crash or an out-of-bounds read (run under the sanitizers).
TEST_F(RealBags, ByteFlipsAreReadOrRefused) {
  const std::string original = ReadBytes(dir_ + "/mcap-talker/talker.mcap");
  const fs::path path = fs::path(sfm::testing::MakeScratchDir("rosbag2_flips")) / "flipped.mcap";
  int refused = 0, read = 0;
  for (size_t position = 0; position < original.size(); position += 13) {
    std::string bytes = original;
    bytes[position] = static_cast<char>(bytes[position] ^ 0x5a);
    WriteBytes(path, bytes);
    Rosbag2Bag bag;
    Status status = bag.Open(path.string());
    if (status.ok())
      status = bag.ReadMessages([](const BagTopic&, const BagMessage&) { return Status::Ok(); });
    if (status.ok()) {
      ++read;
    } else {
      ++refused;
      EXPECT_THAT(status.message(), HasSubstr(path.string()));
    }
  }
  // The chunk and summary CRCs cover all but the header, the data-end record and the footer.
  EXPECT_GT(refused, 0.9 * (refused + read)) << refused << " refused, " << read << " read";
  RecordProperty("refused", refused);
  RecordProperty("read", read);
}

// A CDR Image cut at every length fails to decode with a message, and decodes whole.
TEST(Ros2Messages, TruncatedCdrIsRefused) {
  const std::vector<std::uint8_t> pixels(6 * 4, 7);
  const std::vector<std::uint8_t> bytes = testing::CdrImage(123456789, "camera", 6, 4, "mono8", 6, pixels);
  for (size_t size = 0; size < bytes.size(); ++size) {
    RosImage image;
    const std::vector<std::uint8_t> prefix(bytes.begin(), bytes.begin() + size);
    const Status status = DecodeRosImage(prefix.data(), prefix.size(), "image", &image);
    EXPECT_FALSE(status.ok()) << size;
    EXPECT_THAT(status.message(), HasSubstr("image: ")) << size;
  }
  RosImage image;
  ASSERT_TRUE(DecodeRosImage(bytes.data(), bytes.size(), "image", &image).ok());
  EXPECT_EQ(image.header.stamp, 123456789);
  EXPECT_EQ(image.header.frame_id, "camera");
  EXPECT_EQ(image.data, pixels);
}

// CRCs our writer computes the specification's way: a flipped message byte in an uncompressed
// chunk fails the chunk CRC; in an unchunked file, the data section CRC.
TEST(McapReader, ChunkAndDataSectionCrcMismatches) {
  const fs::path scratch = sfm::testing::MakeScratchDir("rosbag2_crc");
  std::vector<BagMessageSpec> messages;
  for (int i = 0; i < 5; ++i) {
    messages.push_back(
        {"/odom", kRosPoseStamped, i * 100, testing::CdrPoseStamped(i * 100, "odom", Pose3())});
  }
  for (const bool chunked : {true, false}) {
    McapWriteOptions options;
    options.chunked = chunked;
    std::string bytes = testing::WriteMcap(messages, options);
    McapReader good;
    WriteBytes(scratch / "good.mcap", bytes);
    ASSERT_TRUE(good.Open((scratch / "good.mcap").string()).ok());
    int read = 0;
    ASSERT_TRUE(good.ReadMessages([&](const McapChannel&, const McapSchema*, const McapMessage&) {
                      ++read;
                      return Status::Ok();
                    })
                    .ok());
    EXPECT_EQ(read, 5);
    // The last message's last byte (a quaternion's w), well inside the data section.
    const size_t data_end = bytes.rfind(std::string("\x0f\x04\0\0\0\0\0\0\0", 9));
    ASSERT_NE(data_end, std::string::npos);
    bytes[data_end - 1] = static_cast<char>(bytes[data_end - 1] ^ 0x40);
    WriteBytes(scratch / "bad.mcap", bytes);
    McapReader bad;
    ASSERT_TRUE(bad.Open((scratch / "bad.mcap").string()).ok());
    const Status status = bad.ReadMessages(
        [](const McapChannel&, const McapSchema*, const McapMessage&) { return Status::Ok(); });
    ASSERT_FALSE(status.ok());
    EXPECT_THAT(status.message(), HasSubstr(chunked ? "chunk CRC mismatch" : "data section CRC mismatch"));
  }
}

// --- Bags written from a generated sequence -------------------------------------------------

using testing::AppRun;
using testing::ExpectSameSequence;

AppRun Import(const std::string& arguments, const fs::path& scratch) {
  return testing::RunProgram(SFM_IMPORT_SEQUENCE_BINARY, "--format rosbag2 " + arguments, scratch.string());
}

struct BagContent {
  std::string encoding = "mono8";  // mono8, rgb8, bgr8, mono16, png (CompressedImage), jpeg
  int step_padding = 0;            // bytes after each row of a raw image
  bool groundtruth = true;
  std::string distortion_model = "plumb_bob";
  int odometry_frames = -1;           // odometry for the first N frames only (-1: all)
  bool odometry_even_frames = false;  // odometry at the even frames' stamps only (interpolated between)
  int small_frame = -1;               // this frame's image is half size
  std::string image_topic = "/camera/image_raw";
  bool camera_info = true;  // the CameraInfo topic and /tf_static
};

constexpr const char* kBaseFrame = "base_link";

// Messages of a ROS 2 bag holding the sequence: images, camera_info, /odom (Odometry, base_link
// in odom), /groundtruth (PoseStamped), /tf_static with base_link -> camera_link -> camera_optical.
std::vector<BagMessageSpec> SequenceMessages(const Sequence& sequence, const BagContent& content) {
  std::vector<BagMessageSpec> messages;
  const Camera& camera = sequence.calibration.camera;
  // base_link -> camera_link -> camera_optical composes to T_base_camera.
  const Pose3 base_T_link(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                          Eigen::Vector3d(0.1, -0.05, 0.2));
  const Pose3 link_T_optical = base_T_link.Inverse() * sequence.calibration.base_T_camera;
  if (content.camera_info) {
    messages.push_back(
        {"/tf_static", kRosTfMessage, 0,
         testing::CdrTfMessage({{kBaseFrame, "camera_link"}, {"camera_link", "camera_optical"}},
                               {base_T_link, link_T_optical})});
  }
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    const Frame& frame = sequence.frames[i];
    const std::int64_t stamp = std::llround(frame.timestamp * 1e9);
    const std::int64_t received = stamp + 2000000;
    cv::Mat image = cv::imread(sequence.directory + "/" + frame.image_path, cv::IMREAD_UNCHANGED);
    if (static_cast<int>(i) == content.small_frame) cv::resize(cv::Mat(image), image, image.size() / 2);
    std::vector<std::uint8_t> pixels;
    std::string encoding = content.encoding;
    int channels = 1, bytes = 1;
    cv::Mat converted = image;
    if (encoding == "rgb8" || encoding == "bgr8") {
      cv::cvtColor(image, converted, encoding == "rgb8" ? cv::COLOR_GRAY2RGB : cv::COLOR_GRAY2BGR);
      channels = 3;
    } else if (encoding == "mono16") {
      image.convertTo(converted, CV_16U, 16);  // 12-bit data, as many 16-bit cameras give
      bytes = 2;
    }
    if (encoding == "png" || encoding == "jpeg") {
      cv::imencode("." + encoding, image, pixels);
      messages.push_back({content.image_topic + "/compressed", kRosCompressedImage, received,
                          testing::CdrCompressedImage(stamp, "camera_optical", encoding, pixels)});
    } else {
      const int row = converted.cols * channels * bytes;
      for (int r = 0; r < converted.rows; ++r) {
        pixels.insert(pixels.end(), converted.ptr<std::uint8_t>(r), converted.ptr<std::uint8_t>(r) + row);
        pixels.insert(pixels.end(), content.step_padding, 0xab);
      }
      messages.push_back({content.image_topic, kRosImage, received,
                          testing::CdrImage(stamp, "camera_optical", converted.cols, converted.rows, encoding,
                                            row + content.step_padding, pixels)});
    }
    std::vector<double> d(camera.distortion.begin(), camera.distortion.end());
    if (content.distortion_model == "rational_polynomial") d.resize(8, 0.01);
    if (content.distortion_model == "equidistant") d = {0.01, -0.02, 0.03, -0.04};
    if (content.camera_info) {
      messages.push_back(
          {"/camera/camera_info", kRosCameraInfo, received,
           testing::CdrCameraInfo(stamp, "camera_optical", camera.width, camera.height,
                                  content.distortion_model, d, camera.fx, camera.fy, camera.cx, camera.cy)});
    }
    const bool odometry = (content.odometry_frames < 0 || static_cast<int>(i) < content.odometry_frames) &&
                          (!content.odometry_even_frames || i % 2 == 0 || i + 1 == sequence.frames.size());
    if (odometry) {
      messages.push_back({"/odom", kRosOdometry, received,
                          testing::CdrOdometry(stamp, "odom", "base_link", frame.world_T_base_odometry)});
    }
    if (content.groundtruth) {
      messages.push_back({"/groundtruth", kRosPoseStamped, received,
                          testing::CdrPoseStamped(stamp, "map", *frame.world_T_base_groundtruth)});
    }
  }
  return messages;
}

class RosbagRoundTrip : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new std::string(sfm::testing::MakeScratchDir("rosbag2_round_trip"));
    const std::string sequence = *scratch_ + "/sequence";
    const int status = std::system((std::string(SFM_MAKE_SEQUENCE_BINARY) +
                                    " --scene room --frames 8 --output " + sequence + " >/dev/null 2>&1")
                                       .c_str());
    ASSERT_EQ(status, 0);
    sequence_ = new Sequence();
    ASSERT_TRUE(ReadSequence(sequence, sequence_).ok());
  }
  static void TearDownTestSuite() {
    delete sequence_;
    delete scratch_;
  }

  // Writes the bag ("mcap" folder, "mcap-file", "sqlite3" folder) and returns its path.
  static std::string WriteBag(const std::string& name, const std::string& storage, const BagContent& content,
                              const McapWriteOptions& options = McapWriteOptions()) {
    const fs::path dir = fs::path(*scratch_) / name;
    fs::create_directories(dir);
    const std::vector<BagMessageSpec> messages = SequenceMessages(*sequence_, content);
    if (storage == "sqlite3") {
      EXPECT_TRUE(testing::WriteSqliteBag((dir / "bag_0.db3").string(), messages));
      WriteBytes(dir / "metadata.yaml", testing::Rosbag2Metadata("sqlite3", "bag_0.db3", messages));
      return dir.string();
    }
    WriteBytes(dir / "bag_0.mcap", testing::WriteMcap(messages, options));
    if (storage == "mcap-file") return (dir / "bag_0.mcap").string();
    WriteBytes(dir / "metadata.yaml", testing::Rosbag2Metadata("mcap", "bag_0.mcap", messages));
    return dir.string();
  }

  static std::string* scratch_;
  static Sequence* sequence_;
};
std::string* RosbagRoundTrip::scratch_ = nullptr;
Sequence* RosbagRoundTrip::sequence_ = nullptr;

// Every storage and compression, raw and compressed images: the sequence comes back exactly.
TEST_F(RosbagRoundTrip, ImagesBitIdenticalPosesWithin1e9) {
  struct Variant {
    std::string name, storage;
    BagContent content;
    McapWriteOptions mcap;
    bool colour;
  };
  std::vector<Variant> variants;
  McapWriteOptions zstd;
  zstd.compression = "zstd";
  variants.push_back({"mono8_zstd_summary", "mcap", BagContent(), zstd, false});
  McapWriteOptions lz4;
  lz4.compression = "lz4";
  lz4.summary = false;
  lz4.chunk_bytes = 100000;  // several chunks
  BagContent rgb;
  rgb.encoding = "rgb8";
  variants.push_back({"rgb8_lz4_no_summary", "mcap-file", rgb, lz4, true});
  BagContent bgr;
  bgr.encoding = "bgr8";
  bgr.step_padding = 8;
  McapWriteOptions none;
  variants.push_back({"bgr8_padded_uncompressed", "mcap", bgr, none, true});
  BagContent mono16;
  mono16.encoding = "mono16";
  variants.push_back({"mono16_sqlite3", "sqlite3", mono16, none, false});
  BagContent png;
  png.encoding = "png";
  McapWriteOptions unchunked;
  unchunked.chunked = false;
  variants.push_back({"png_unchunked", "mcap", png, unchunked, false});
  for (const Variant& v : variants) {
    const std::string bag = WriteBag(v.name, v.storage, v.content, v.mcap);
    const std::string output = *scratch_ + "/" + v.name + "_imported";
    const AppRun run = Import("--input " + bag + " --output " + output + " --groundtruth_topic /groundtruth",
                              fs::path(*scratch_));
    ASSERT_EQ(run.exit_status, 0) << v.name << ": " << run.errors;
    SCOPED_TRACE(v.name);
    ExpectSameSequence(*sequence_, output, v.colour);
  }
}

// junction_sfm on the imported bag writes the same outputs as on the sequence it came from.
TEST_F(RosbagRoundTrip, JunctionSfmGivesTheSameOutputs) {
  const std::string bag = WriteBag("sfm", "mcap", BagContent());
  const std::string imported = *scratch_ + "/sfm_imported";
  // The generated sequence's odometry noise model, so that both runs weight the odometry alike.
  const OdometryNoise& noise = sequence_->calibration.odometry_noise;
  char noise_flag[128];
  std::snprintf(noise_flag, sizeof(noise_flag), "%.17g,%.17g", noise.translation_sigma, noise.rotation_sigma);
  ASSERT_EQ(Import("--input " + bag + " --output " + imported +
                       " --groundtruth_topic /groundtruth --odometry_noise " + noise_flag,
                   fs::path(*scratch_))
                .exit_status,
            0);
  for (const std::string& which : {std::string("original"), std::string("imported")}) {
    const std::string sequence = which == "original" ? sequence_->directory : imported;
    const AppRun run =
        testing::RunProgram(SFM_JUNCTION_SFM_BINARY,
                            "--sequence " + sequence + " --output " + *scratch_ + "/out_" + which, *scratch_);
    ASSERT_EQ(run.exit_status, 0) << run.errors;
  }
  const std::map<std::string, std::string> a = sfm::testing::ReadTree(*scratch_ + "/out_original");
  const std::map<std::string, std::string> b = sfm::testing::ReadTree(*scratch_ + "/out_imported");
  ASSERT_EQ(a.size(), b.size());
  int compared = 0;
  for (const auto& [name, bytes] : a) {
    // Run times and the sequence's path: the log, the metrics' time_s and the report page.
    if (name == "metrics.json" || name == "junction_sfm.log" || name == "report.html") continue;
    EXPECT_EQ(b.at(name), bytes) << name;
    ++compared;
  }
  EXPECT_GT(compared, 10);
}

// Odometry at every other image: the others get the pose halfway (slerp), within 1e-12.
TEST_F(RosbagRoundTrip, OdometryInterpolatedAtImageStamps) {
  BagContent content;
  content.odometry_even_frames = true;
  const std::string bag = WriteBag("interpolated", "mcap", content);
  const std::string output = *scratch_ + "/interpolated_imported";
  ASSERT_EQ(Import("--input " + bag + " --output " + output, fs::path(*scratch_)).exit_status, 0);
  Sequence imported;
  ASSERT_TRUE(ReadSequence(output, &imported).ok());
  ASSERT_EQ(imported.frames.size(), 8u);
  for (size_t i = 1; i + 1 < 8; i += 2) {
    const Pose3 expected = InterpolatePose(sequence_->frames[i - 1].world_T_base_odometry,
                                           sequence_->frames[i + 1].world_T_base_odometry, 0.5);
    EXPECT_LT((imported.frames[i].world_T_base_odometry.translation - expected.translation).norm(), 1e-12);
    EXPECT_LT(RotationAngle(imported.frames[i].world_T_base_odometry.rotation, expected.rotation), 1e-12);
  }
}

// An equidistant (fisheye) CameraInfo becomes SPEC's distortion_model: equidistant with its four
// coefficients exactly.
TEST_F(RosbagRoundTrip, EquidistantCameraInfoIsWrittenAsSuch) {
  BagContent content;
  content.distortion_model = "equidistant";
  const std::string bag = WriteBag("equidistant", "mcap", content);
  const std::string output = *scratch_ + "/equidistant_imported";
  const AppRun run = Import("--input " + bag + " --output " + output, fs::path(*scratch_));
  ASSERT_EQ(run.exit_status, 0) << run.errors;
  cv::FileStorage yaml(output + "/sequence.yaml", cv::FileStorage::READ);
  EXPECT_EQ(static_cast<std::string>(yaml["distortion_model"]), "equidistant");
  cv::Mat k;
  yaml["distortion_coefficients"] >> k;
  ASSERT_EQ(k.total(), 4u);
  const double expected[4] = {0.01, -0.02, 0.03, -0.04};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(k.at<double>(i), expected[i]) << i;
  Sequence imported;
  ASSERT_TRUE(ReadSequence(output, &imported).ok());
  EXPECT_EQ(imported.calibration.camera.model, DistortionModel::kEquidistant);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(imported.calibration.camera.distortion[i], expected[i]) << i;
}

// A bag without CameraInfo and /tf_static: refused by name, imported with --calibration (here the
// sequence's own sequence.yaml, OpenCV layout) giving the camera and T_base_camera.
TEST_F(RosbagRoundTrip, CalibrationFileReplacesCameraInfo) {
  BagContent content;
  content.camera_info = false;
  const std::string bag = WriteBag("no_camera_info", "mcap", content);
  const std::string output = *scratch_ + "/no_camera_info_imported";
  AppRun run = Import("--input " + bag + " --output " + output, fs::path(*scratch_));
  EXPECT_EQ(run.exit_status, 1);
  EXPECT_THAT(run.errors, HasSubstr(bag + ": no camera_info topic (sensor_msgs/msg/CameraInfo)"));
  run = Import("--input " + bag + " --output " + output + " --groundtruth_topic /groundtruth --calibration " +
                   sequence_->directory + "/sequence.yaml",
               fs::path(*scratch_));
  ASSERT_EQ(run.exit_status, 0) << run.errors;
  ExpectSameSequence(*sequence_, output, false);
}

// --every, the time window and the keyframe motion pick the frames they say.
TEST_F(RosbagRoundTrip, EveryWindowAndKeyframes) {
  const std::string bag = WriteBag("selection", "mcap-file", BagContent());
  const auto frames = [&](const std::string& flags) {
    const std::string output = *scratch_ + "/selection_imported";
    const AppRun run =
        Import("--input " + bag + " --output " + output + " --overwrite " + flags, fs::path(*scratch_));
    EXPECT_EQ(run.exit_status, 0) << flags << ": " << run.errors;
    Sequence imported;
    EXPECT_TRUE(ReadSequence(output, &imported).ok());
    std::vector<double> stamps;
    for (const Frame& frame : imported.frames) stamps.push_back(std::round(frame.timestamp * 10));
    return stamps;
  };
  EXPECT_EQ(frames("--every 3"), (std::vector<double>{0, 3, 6}));
  EXPECT_EQ(frames("--start_time 0.2 --end_time 0.5"), (std::vector<double>{2, 3, 4, 5}));
  EXPECT_EQ(frames("--start_time 0.25 --every 2"), (std::vector<double>{3, 5, 7}));
  // Keyframes: the step between kept frames is at least --min_motion of odometry travel.
  double step = 0;
  for (size_t i = 1; i < sequence_->frames.size(); ++i) {
    step = std::max(step, (sequence_->frames[i].world_T_base_odometry.translation -
                           sequence_->frames[i - 1].world_T_base_odometry.translation)
                              .norm());
  }
  const std::vector<double> kept = frames("--min_motion " + std::to_string(1.5 * step));
  ASSERT_GE(kept.size(), 2u);
  EXPECT_LT(kept.size(), sequence_->frames.size());
  for (size_t i = 1; i < kept.size(); ++i) {
    const Pose3& a = sequence_->frames[static_cast<int>(kept[i - 1])].world_T_base_odometry;
    const Pose3& b = sequence_->frames[static_cast<int>(kept[i])].world_T_base_odometry;
    EXPECT_GE((a.translation - b.translation).norm(), 1.5 * step - 1e-12);
  }
}

// Bad input: exit 1, one line naming the bag, the topic and the problem, and no output at all.
TEST_F(RosbagRoundTrip, BadInputIsOneLineAndNoOutput) {
  struct Case {
    std::string name, flags, expected;
    BagContent content;
    McapWriteOptions mcap;
  };
  std::vector<Case> cases;
  cases.push_back(
      {"no_topic", "--image_topic /nope", "no topic /nope (image topics: /camera/image_raw", {}, {}});
  BagContent two;
  McapWriteOptions with_second;
  with_second.empty_topics = {"/camera2/image_raw sensor_msgs/msg/Image"};
  cases.push_back({"ambiguous", "",
                   "2 image topics, choose one with --image_topic: /camera/image_raw "
                   "(sensor_msgs/msg/Image, 8), /camera2/image_raw (sensor_msgs/msg/Image, 0)",
                   two, with_second});
  cases.push_back({"empty", "--image_topic /camera2/image_raw",
                   "/camera2/image_raw: the image topic is empty", two, with_second});
  BagContent resized;
  resized.small_frame = 5;
  cases.push_back({"changing_size",
                   "",
                   "/camera/image_raw: message 5: image is 320x240, earlier ones 640x480",
                   resized,
                   {}});
  BagContent short_odometry;
  short_odometry.odometry_frames = 2;
  cases.push_back({"odometry_stops",
                   "",
                   "/odom: odometry stops at 0.1 s, before the images (to 0.7 s",
                   short_odometry,
                   {}});
  BagContent rational;
  rational.distortion_model = "rational_polynomial";
  cases.push_back(
      {"rational",
       "",
       "/camera/camera_info: distortion model rational_polynomial (8 coefficients) is not supported",
       rational,
       {}});
  BagContent bayer;
  bayer.encoding = "bayer_rggb8";
  cases.push_back({"bayer", "", "image encoding 'bayer_rggb8' is not supported", bayer, {}});
  McapWriteOptions json;
  json.message_encoding = "json";
  cases.push_back({"json", "", "/camera/image_raw: message encoding 'json', expected cdr", {}, json});
  McapWriteOptions idl;
  idl.schema_encoding = "jsonschema";
  cases.push_back({"schema", "", "schema encoding 'jsonschema', expected ros2msg or ros2idl", {}, idl});
  cases.push_back({"wrong_type",
                   "--image_topic /odom",
                   "/odom: type nav_msgs/msg/Odometry, the image topic must be",
                   {},
                   {}});
  McapWriteOptions unknown;
  unknown.compression = "brotli";
  cases.push_back({"compression", "", "unknown chunk compression 'brotli'", {}, unknown});
  for (const Case& c : cases) {
    const std::string bag = WriteBag("bad_" + c.name, "mcap", c.content, c.mcap);
    const std::string output = *scratch_ + "/bad_" + c.name + "_imported";
    const AppRun run = Import("--input " + bag + " --output " + output + " " + c.flags, fs::path(*scratch_));
    EXPECT_EQ(run.exit_status, 1) << c.name;
    EXPECT_EQ(std::count(run.errors.begin(), run.errors.end(), '\n'), 1) << c.name << ": " << run.errors;
    EXPECT_THAT(run.errors, HasSubstr("import_sequence: " + bag)) << c.name;
    EXPECT_THAT(run.errors, HasSubstr(c.expected)) << c.name;
    EXPECT_FALSE(fs::exists(output)) << c.name;
    for (const fs::directory_entry& entry : fs::directory_iterator(*scratch_)) {
      EXPECT_EQ(entry.path().filename().string().find(".bad_" + c.name + "_imported"), std::string::npos)
          << "left behind: " << entry.path();
    }
  }
}

}  // namespace
}  // namespace sfm

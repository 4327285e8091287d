// The committed default sequence (sequences/default) is exactly what the generator makes with its
// default options, which is what sequences/regenerate_default.sh runs.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "sequences/generator/ground_truth.h"
#include "sequences/generator/sequence_writer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

using testing::ReadFile;
using testing::ReadTree;

TEST(DefaultSequenceTest, ScriptRunsMakeSequenceWithDefaultOptions) {
  const std::string script = ReadFile(fs::path(testing::SourceDir()) / "sequences" / "regenerate_default.sh");
  ASSERT_FALSE(script.empty());
  // The make_sequence command line: only --output and --overwrite, so the defaults apply.
  const size_t at = script.find("bin/make_sequence\"");
  ASSERT_NE(at, std::string::npos) << "regenerate_default.sh does not run make_sequence";
  const size_t end = script.find('\n', at);
  std::istringstream arguments(script.substr(at, end - at));
  std::string argument;
  arguments >> argument;  // the program
  int count = 0;
  while (arguments >> argument) {
    ++count;
    EXPECT_TRUE(argument == "--output" || argument == "--overwrite" || argument[0] != '-')
        << "regenerate_default.sh passes " << argument << ": the default sequence must use default options";
  }
  EXPECT_EQ(count, 3);  // --output <dir> --overwrite
}

TEST(DefaultSequenceTest, RegeneratesBitForBit) {
  const fs::path committed = fs::path(testing::SourceDir()) / "sequences" / "default";
  ASSERT_TRUE(fs::exists(committed / "sequence.yaml")) << committed << " is missing";
  const std::string scratch = testing::MakeScratchDir("generator_default");
  GenerationReport report;
  const Status status = GenerateSequence(GeneratorOptions(), scratch, /*overwrite=*/false, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  const auto expected = ReadTree(committed), actual = ReadTree(scratch);
  for (const auto& [name, bytes] : actual) {
    ASSERT_TRUE(expected.count(name)) << name << " is not in sequences/default: run sequences/regenerate_default.sh";
    EXPECT_TRUE(bytes == expected.at(name)) << name << " differs from sequences/default";
  }
  for (const auto& [name, bytes] : expected) {
    if (name == "README.md") continue;
    EXPECT_TRUE(actual.count(name)) << name << " is in sequences/default but not generated";
  }
  EXPECT_GE(report.frames, 40);
  EXPECT_LT(report.bytes, /*max_bytes=*/10'000'000u);
}

TEST(DefaultSequenceTest, TruthHasEveryJunctionType) {
  GroundTruth truth;
  const Status status = ReadGroundTruth((fs::path(testing::SourceDir()) / "sequences" / "default").string(), &truth);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_GE(truth.frames.size(), 40u);
  std::map<std::string, int> types;
  int occlusions = 0;
  for (const FrameTruth& frame : truth.frames) {
    for (const VisibleVertex& vertex : frame.vertices) ++types[vertex.type];
    for (const VisibleSegment& segment : frame.segments) {
      occlusions += (segment.end[0] == SegmentEnd::kOcclusion) + (segment.end[1] == SegmentEnd::kOcclusion);
    }
  }
  // Per frame on average: plenty of L and ARROW, some Y and T; X from the quartered posters.
  const int frames = static_cast<int>(truth.frames.size());
  EXPECT_GT(types["L"], 20 * frames);
  EXPECT_GT(types["ARROW"], 5 * frames);
  EXPECT_GT(types["Y"], 2 * frames);
  EXPECT_GT(types["T"], 2 * frames);
  EXPECT_GT(types["X"], 10);
  EXPECT_GT(occlusions, 20 * frames);  // T junctions made by occlusion
}

}  // namespace
}  // namespace sfm

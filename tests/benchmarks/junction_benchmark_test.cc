// The list parsing and sequence discovery of benchmark_junctions (junction_benchmark.h): exact
// values, and a one-line error naming the flag for bad input.
#include "benchmarks/junctions/junction_benchmark.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/test_data.h"

namespace sfm {
namespace {

TEST(JunctionBenchmarkTest, ContactDistancesParseInOrder) {
  std::vector<double> contacts;
  ASSERT_TRUE(ParseContactDistances("3,5,,2.5", &contacts).ok());
  EXPECT_EQ(contacts, (std::vector<double>{3, 5, 2.5}));
}

TEST(JunctionBenchmarkTest, ContactDistancesRejectBadInput) {
  std::vector<double> contacts;
  for (const char* text : {"", "3,x", "0", "100", "-1", "3px"}) {
    const Status status = ParseContactDistances(text, &contacts);
    EXPECT_FALSE(status.ok()) << text;
    EXPECT_NE(status.message().find("--gt_contact_px"), std::string::npos) << status.message();
  }
}

TEST(JunctionBenchmarkTest, SegmentMethodsKeepTheBaseOptions) {
  SegmentDetectorOptions base;
  base.min_length = 17;
  std::vector<JunctionBenchmarkMethod> methods;
  ASSERT_TRUE(ParseSegmentMethods("fast,reference", base, &methods).ok());
  ASSERT_EQ(methods.size(), 2u);
  EXPECT_EQ(methods[0].name, "fast");
  EXPECT_EQ(methods[0].options.method, SegmentMethod::kFast);
  EXPECT_EQ(methods[1].name, "reference");
  EXPECT_EQ(methods[1].options.method, SegmentMethod::kReference);
  EXPECT_EQ(methods[1].options.min_length, 17);
  EXPECT_FALSE(ParseSegmentMethods("fast,lsd", base, &methods).ok());
  EXPECT_FALSE(ParseSegmentMethods(",", base, &methods).ok());
}

TEST(JunctionBenchmarkTest, GivenSequencesFindTheirNoiseFreeTwin) {
  const std::string dir = testing::MakeScratchDir("junction_benchmark_sequences");
  std::filesystem::create_directories(dir + "/a-noise-free");
  std::ofstream(dir + "/a-noise-free/images.txt") << "";
  const std::vector<JunctionBenchmarkSequence> sequences = GivenSequences({dir + "/a", dir + "/b"});
  ASSERT_EQ(sequences.size(), 2u);
  EXPECT_EQ(sequences[0].name, "a");
  EXPECT_EQ(sequences[0].clean, dir + "/a-noise-free");
  EXPECT_EQ(sequences[1].name, "b");
  EXPECT_EQ(sequences[1].clean, "");
}

}  // namespace
}  // namespace sfm

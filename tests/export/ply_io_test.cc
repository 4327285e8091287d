#include "backend/export/ply_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "tests/test_data.h"

namespace sfm {
namespace {

using testing::ReadFile;

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(PlyTest, WritesTheSpecHeaderAndShortestNumbers) {
  const std::string path = testing::MakeScratchDir("ply_header") + "/wireframe.ply";
  ReconstructedWireframe wireframe;
  wireframe.vertices = {{0.1, -2, 3.5}, {1e-7, 0, 12345678.25}, {-0.0, 1, 2}};
  wireframe.edges = {{0, 1}, {1, 2}};
  ASSERT_TRUE(WritePly(path, wireframe).ok());
  EXPECT_EQ(ReadFile(path),
            "ply\n"
            "format ascii 1.0\n"
            "element vertex 3\n"
            "property double x\n"
            "property double y\n"
            "property double z\n"
            "element edge 2\n"
            "property int vertex1\n"
            "property int vertex2\n"
            "end_header\n"
            "0.1 -2 3.5\n"
            "1e-07 0 12345678.25\n"
            "0 1 2\n"
            "0 1\n"
            "1 2\n");
}

TEST(PlyTest, WriteReadRoundTripIsExact) {
  const std::string path = testing::MakeScratchDir("ply_round_trip") + "/wireframe.ply";
  ReconstructedWireframe wireframe;
  for (int i = 0; i < 50; ++i) wireframe.vertices.push_back(Eigen::Vector3d::Random() * 100);
  for (int i = 0; i + 1 < 50; i += 2) wireframe.edges.emplace_back(i, i + 1);
  ASSERT_TRUE(WritePly(path, wireframe).ok());
  ReconstructedWireframe back;
  const Status read = ReadPly(path, &back);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(back.vertices, wireframe.vertices);
  EXPECT_EQ(back.edges, wireframe.edges);
}

// SPEC section 3 allows extra vertex properties after x y z: track_id, written and read back; a
// track_ids of another size than the vertices is refused.
TEST(PlyTest, TrackIdsAreAVertexPropertyAfterXyz) {
  const std::string dir = testing::MakeScratchDir("ply_track_id");
  ReconstructedWireframe wireframe;
  wireframe.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  wireframe.edges = {{0, 1}, {1, 2}};
  wireframe.track_ids = {7, -1, 0};
  ASSERT_TRUE(WritePly(dir + "/wireframe.ply", wireframe).ok());
  EXPECT_EQ(
      ReadFile(dir + "/wireframe.ply"),
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "property int track_id\nelement edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 7\n1 0 0 -1\n1 2 0 0\n0 1\n1 2\n");
  ReconstructedWireframe back;
  ASSERT_TRUE(ReadPly(dir + "/wireframe.ply", &back).ok());
  EXPECT_EQ(back.track_ids, wireframe.track_ids);
  EXPECT_EQ(back.vertices, wireframe.vertices);
  wireframe.track_ids.pop_back();
  EXPECT_FALSE(WritePly(dir + "/short.ply", wireframe).ok());
  EXPECT_FALSE(std::filesystem::exists(dir + "/short.ply"));
}

TEST(PlyTest, AnEmptyWireframeIsAValidFile) {
  const std::string path = testing::MakeScratchDir("ply_empty") + "/wireframe.ply";
  ASSERT_TRUE(WritePly(path, ReconstructedWireframe()).ok());
  ReconstructedWireframe back;
  ASSERT_TRUE(ReadPly(path, &back).ok());
  EXPECT_TRUE(back.vertices.empty());
  EXPECT_TRUE(back.edges.empty());
}

TEST(PlyTest, BadWireframesAreRejectedWithoutAFile) {
  const std::string dir = testing::MakeScratchDir("ply_bad");
  ReconstructedWireframe out_of_range;
  out_of_range.vertices = {{0, 0, 0}, {1, 1, 1}};
  out_of_range.edges = {{0, 2}};
  const Status edge = WritePly(dir + "/edge.ply", out_of_range);
  EXPECT_FALSE(edge.ok());
  EXPECT_NE(edge.message().find("edge 0 refers to vertex 2"), std::string::npos) << edge.message();

  ReconstructedWireframe not_finite;
  not_finite.vertices = {{0, std::numeric_limits<double>::quiet_NaN(), 0}};
  const Status nan = WritePly(dir + "/nan.ply", not_finite);
  EXPECT_FALSE(nan.ok());
  EXPECT_NE(nan.message().find("vertex 0"), std::string::npos) << nan.message();
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(PlyTest, ReadsOtherWritersFilesWithExtraProperties) {
  const std::string path = testing::MakeScratchDir("ply_foreign") + "/foreign.ply";
  WriteText(path,
            "ply\n"
            "format ascii 1.0\n"
            "comment written by hand\n"
            "element vertex 2\n"
            "property float x\n"
            "property float y\n"
            "property float z\n"
            "property uchar red\n"
            "element face 1\n"
            "property list uchar int vertex_indices\n"
            "element edge 1\n"
            "property int vertex1\n"
            "property int vertex2\n"
            "end_header\n"
            "1 2 3 255\n"
            "4 5 6 0\n"
            "3 0 1 1\n"
            "1 0\n");
  ReconstructedWireframe back;
  const Status read = ReadPly(path, &back);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(back.vertices.size(), 2u);
  EXPECT_EQ(back.vertices[1], Eigen::Vector3d(4, 5, 6));
  ASSERT_EQ(back.edges.size(), 1u);
  EXPECT_EQ(back.edges[0], std::make_pair(1, 0));
}

TEST(PlyTest, ReaderNamesTheFileAndLineOfAProblem) {
  const std::string dir = testing::MakeScratchDir("ply_read_bad");
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
      "property double z\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "end_header\n";
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"solid\n", "bad.ply:1: not a PLY file"},
      {"ply\nformat binary_little_endian 1.0\nend_header\n", "bad.ply:2: PLY format 'binary_little_endian'"},
      {header + "1 2\n0 0\n", "bad.ply:11: expected 3 numbers, found 2"},
      {header + "1 2 x\n0 0\n", "bad.ply:11: vertex coordinates are not finite numbers"},
      {header + "1 2 3\n", "bad.ply: ends after 0 of 1 edge lines"},
      {header + "1 2 3\n0 1\n", "bad.ply: edge 0 1 refers to a vertex outside the 1 vertices"},
  };
  for (const auto& c : cases) {
    WriteText(dir + "/bad.ply", c.text);
    ReconstructedWireframe back;
    const Status read = ReadPly(dir + "/bad.ply", &back);
    EXPECT_FALSE(read.ok()) << c.text;
    EXPECT_NE(read.message().find(c.expected), std::string::npos) << read.message();
  }
}

}  // namespace
}  // namespace sfm

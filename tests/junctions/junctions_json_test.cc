#include "frontend/junctions/junctions_json.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

Junction SpecExample() {
  Junction j;
  j.id = 0;
  j.location = Eigen::Vector2d(311.42, 120.07);
  j.type = JunctionType::kY;
  j.score = 0.83;
  j.segments = {{Eigen::Vector2d(350.1, 118.9), 3},
                {Eigen::Vector2d(290.0, 180.2), 4},
                {Eigen::Vector2d(300.7, 60.3), 5}};
  return j;
}

TEST(JunctionsJsonTest, ExactLayoutOfSpecSection3) {
  const std::string expected =
      "{\"frame\": 12, \"image\": \"images/000012.png\", \"width\": 640, \"height\": 480,\n"
      " \"junctions\": [\n"
      "   {\"id\": 0, \"x\": 311.420, \"y\": 120.070, \"type\": \"Y\", \"score\": 0.83,\n"
      "    \"segments\": [[350.100, 118.900], [290.000, 180.200], [300.700, 60.300]]}\n"
      " ]}\n";
  EXPECT_EQ(JunctionsToJson(12, "images/000012.png", 640, 480, {SpecExample()}), expected);
  EXPECT_EQ(JunctionsToJson(3, "a.png", 10, 20, {}),
            "{\"frame\": 3, \"image\": \"a.png\", \"width\": 10, \"height\": 20,\n \"junctions\": []}\n");
}

TEST(JunctionsJsonTest, RoundTrip) {
  Junctions junctions = {SpecExample(), SpecExample()};
  junctions[1].id = 1;
  junctions[1].type = JunctionType::kArrow;
  junctions[1].score = 1.2345678e-3;
  junctions[1].location = Eigen::Vector2d(-0.0004, 1e4 / 3);
  junctions[1].segments.pop_back();
  const std::string image = "dir with \"quotes\"\\and\ttab/ü.png";
  const std::string json = JunctionsToJson(7, image, 720, 576, junctions);

  JunctionsFile file;
  const Status status = JunctionsFromJson(json, "000007.json", &file);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(file.frame, 7);
  EXPECT_EQ(file.image, image);
  EXPECT_EQ(file.width, 720);
  EXPECT_EQ(file.height, 576);
  ASSERT_EQ(file.junctions.size(), junctions.size());
  for (size_t j = 0; j < junctions.size(); ++j) {
    const Junction& a = junctions[j];
    const Junction& b = file.junctions[j];
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.type, a.type);
    // Three decimals: each coordinate within half a thousandth of a pixel; six significant digits.
    EXPECT_NEAR(b.location.x(), a.location.x(), 5e-4);
    EXPECT_NEAR(b.location.y(), a.location.y(), 5e-4);
    EXPECT_NEAR(b.score, a.score, 5e-6 * a.score);
    ASSERT_EQ(b.NumSegments(), a.NumSegments());
    for (int i = 0; i < a.NumSegments(); ++i) {
      EXPECT_NEAR(b.segments[i].end.x(), a.segments[i].end.x(), 5e-4);
      EXPECT_NEAR(b.segments[i].end.y(), a.segments[i].end.y(), 5e-4);
      EXPECT_EQ(b.segments[i].line_segment, -1);  // not stored in the file
    }
  }
  // Writing what was read gives the same text.
  EXPECT_EQ(JunctionsToJson(file.frame, file.image, file.width, file.height, file.junctions), json);
}

TEST(JunctionsJsonTest, ReadsAnyKeyOrderAndIgnoresUnknownKeys) {
  const std::string json = R"({"junctions": [{"segments": [[1, 2], [3e0, -4.5]], "score": 1, "type": "L",
      "y": 2, "x": 1, "id": 9, "extra": [true, false, null, {}]}], "height": 2, "width": 1,
      "image": "\u00fc\ud83d\ude00", "frame": 0, "note": "x"})";
  JunctionsFile file;
  const Status status = JunctionsFromJson(json, "f.json", &file);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(file.image, "\xc3\xbc\xf0\x9f\x98\x80");
  ASSERT_EQ(file.junctions.size(), 1u);
  EXPECT_EQ(file.junctions[0].id, 9);
  EXPECT_EQ(file.junctions[0].segments[1].end, Eigen::Vector2d(3, -4.5));
}

TEST(JunctionsJsonTest, ErrorsNameTheFileAndTheProblem) {
  const std::string good = JunctionsToJson(1, "a.png", 10, 10, {SpecExample()});
  struct Case {
    std::string json, message;
  };
  const std::vector<Case> cases = {
      {"", "f.json: offset 0: unexpected end"},
      {"{\"frame\": 1,", "f.json: offset 12: expected a key string"},
      {"[1, 2]", "f.json: not a JSON object"},
      {good + "x", "f.json: offset " + std::to_string(good.size()) + ": unexpected text after the end"},
      {R"({"image": "a", "width": 1, "height": 1, "junctions": []})",
       "f.json: \"frame\" missing or not a number"},
      {R"({"frame": 1.5, "image": "a", "width": 1, "height": 1, "junctions": []})",
       "f.json: \"frame\" is not an integer"},
      {R"({"frame": 1, "image": "a", "width": 1, "height": 1, "junctions": [{"id": 0, "x": 1, "y": 1,
          "type": "Q", "score": 1, "segments": []}]})",
       "f.json: junctions[0]: unknown type \"Q\""},
      {R"({"frame": 1, "image": "a", "width": 1, "height": 1, "junctions": [{"id": 0, "x": 1, "y": 1,
          "type": "L", "score": 1, "segments": [[1, 2, 3]]}]})",
       "f.json: junctions[0]: a segment end-point is not [x, y]"},
      {R"({"frame": 1, "image": "a", "width": 1, "height": 1, "junctions": [], "x": 1e999})",
       "f.json: offset 74: malformed number"},
      {std::string(100, '['), "f.json: offset 33: nested too deeply"},
  };
  for (const Case& c : cases) {
    JunctionsFile file;
    const Status status = JunctionsFromJson(c.json, "f.json", &file);
    EXPECT_FALSE(status.ok()) << c.json;
    EXPECT_EQ(status.message(), c.message) << c.json;
  }
}

}  // namespace
}  // namespace sfm

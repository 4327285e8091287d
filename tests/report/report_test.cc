#include "pipeline/report/report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "backend/metrics/drift.h"
#include "pipeline/report/assets.h"
#include "pipeline/report/base64.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;
constexpr int kFrames = 6;

// A camera looking along the base's x axis (camera z = base x, camera x = -base y, camera y = -base z).
Pose3 BaseTCamera() {
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return Pose3(R, Eigen::Vector3d(0.1, 0, 0.5));
}

Pose3 Planar(double x, double y, double yaw) {
  return Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(x, y, 0));
}

Junction MakeJunction(int id, double x, double y, int segments) {
  Junction j;
  j.id = id;
  j.location = Eigen::Vector2d(x, y);
  j.type = segments == 2 ? JunctionType::kL : JunctionType::kY;
  for (int s = 0; s < segments; ++s) {
    const double angle = 2 * kPi * s / segments + 0.3;
    j.segments.push_back({j.location + 25 * Eigen::Vector2d(std::cos(angle), std::sin(angle)), s});
  }
  return j;
}

// Five frames of a robot driving a gentle curve on the floor, with junctions, matches and a few
// 3D points and lines: enough for every section of the report.
struct HandBuiltRun {
  Sequence sequence;
  PipelineResult result;
  std::vector<cv::Mat> images;

  HandBuiltRun() {
    sequence.directory = "/nonexistent/hand_built";
    Camera& camera = sequence.calibration.camera;
    camera.width = 160, camera.height = 120, camera.fx = camera.fy = 100, camera.cx = 79.5, camera.cy = 59.5;
    sequence.calibration.base_T_camera = BaseTCamera();
    sequence.has_groundtruth = true;
    std::vector<Pose3> truth;
    for (int i = 0; i < kFrames; ++i) {
      Frame frame;
      frame.index = i;
      frame.timestamp = 0.1 * i;
      char path[32];
      std::snprintf(path, sizeof(path), "images/%06d.png", i);
      frame.image_path = path;
      frame.world_T_base_groundtruth = Planar(0.3 * i, 0.02 * i * i, 0.05 * i);
      frame.world_T_base_odometry = Planar(0.31 * i, 0.03 * i * i, 0.06 * i);
      sequence.frames.push_back(frame);
      result.world_T_camera_odometry.push_back(frame.world_T_base_odometry * BaseTCamera());
      result.world_T_camera_refined.push_back(Planar(0.301 * i, 0.021 * i * i, 0.051 * i) * BaseTCamera());
      truth.push_back(*frame.world_T_base_groundtruth * BaseTCamera());

      result.junctions.push_back({MakeJunction(0, 40 + 3 * i, 40, 2), MakeJunction(1, 100 + 2 * i, 70, 3),
                                  MakeJunction(2, 60, 90 - i, 3)});
      cv::Mat image(camera.height, camera.width, CV_8UC1, cv::Scalar(90));
      cv::rectangle(image, cv::Rect(30 + 3 * i, 30, 70, 50), cv::Scalar(200), cv::FILLED);
      images.push_back(image);
    }
    result.world_T_camera_truth = truth;
    for (int a = 0; a + 1 < kFrames; ++a) {
      for (int b = a + 1; b <= std::min(a + 2, kFrames - 1); ++b) {
        FramePairMatches pair;
        pair.frame_a = a, pair.frame_b = b;
        pair.matches = {{0, 0, 0.9, 0}, {1, 1, 0.8, 0}};
        if (b == a + 1) pair.matches.push_back({2, 2, 0.7, 1});
        result.pairs.push_back(pair);
      }
    }
    JunctionTrack track;
    track.id = 0;
    for (int i = 0; i < kFrames; ++i) track.views.push_back({i, 1, {0, 1, 2}});
    result.tracks.push_back(track);
    for (int k = 0; k < 4; ++k) {
      PointLandmark point;
      point.track_id = k;
      point.position = Eigen::Vector3d(3 + 0.5 * k, -1 + 0.7 * k, 0.3 * k);
      result.landmarks.points.push_back(point);
      LineLandmark line;
      line.end0 = point.position;
      line.end1 = point.position + Eigen::Vector3d(0, 0, 1);
      line.direction = Eigen::Vector3d::UnitZ();
      line.point = line.end0;
      line.point_landmark = k;
      result.landmarks.lines.push_back(line);
    }
    result.wireframe_landmarks = result.landmarks;  // all drawn
    result.drift_odometry = ComputeDrift(result.world_T_camera_odometry, truth);
    result.drift_refined = ComputeDrift(result.world_T_camera_refined, truth);
    result.times = {1.5, 0.25, 2.0, 3.9};
  }
};

using testing::ReadFile;

int Count(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// The text between the first `begin` and the next `end` ("" when absent: the test then fails).
std::string Between(const std::string& text, const std::string& begin, const std::string& end) {
  const size_t from = text.find(begin);
  EXPECT_NE(from, std::string::npos) << begin;
  if (from == std::string::npos) return "";
  const size_t to = text.find(end, from + begin.size());
  EXPECT_NE(to, std::string::npos) << end;
  return text.substr(from + begin.size(), to - from - begin.size());
}

std::string PercentDecoded(const std::string& text) {
  std::string decoded;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      decoded += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += text[i];
    }
  }
  return decoded;
}

// Decodes every data URI of the page of the given type (png: the plots, jpeg: the match
// pictures); returns how many there were (test fails on a bad one).
int CheckEmbeddedImages(const std::string& html, const std::string& type = "png") {
  const std::string prefix = "data:image/" + type + ";base64,";
  int count = 0;
  for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1)) {
    const size_t begin = at + prefix.size(), end = html.find('"', begin);
    EXPECT_NE(end, std::string::npos);
    std::string encoded;
    EXPECT_TRUE(Base64Decode(html.substr(begin, end - begin), &encoded)) << "image " << count;
    const cv::Mat image = cv::imdecode(std::vector<uchar>(encoded.begin(), encoded.end()), cv::IMREAD_UNCHANGED);
    EXPECT_FALSE(image.empty()) << "image " << count;
    ++count;
  }
  return count;
}

TEST(ReportTest, WritesASelfContainedPageWithEverySection) {
  const HandBuiltRun run;
  const std::string dir = testing::MakeScratchDir("report_full");
  ASSERT_TRUE(WriteReport(run.sequence, run.result, run.images, dir).ok());
  // Only report.html: the temporary file was renamed into place.
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename().string());
  ASSERT_EQ(files, std::vector<std::string>{"report.html"});
  const std::string html = ReadFile(dir + "/report.html");

  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  for (const char* section : {"id=\"summary\"", "id=\"trajectories\"", "id=\"errors\"", "id=\"junctions\"",
                              "id=\"matches\"", "id=\"match-images\"", "id=\"wireframe\""}) {
    EXPECT_NE(html.find(section), std::string::npos) << section;
  }
  for (const char* text : {"ATE", "RPE", "Stage times", "odometry", "refined", "3D lines", "3D points", "tracks",
                           "Frames 0 (left) and 1 (right): 3 matches of 3 and 3 junctions"}) {
    EXPECT_NE(html.find(text), std::string::npos) << text;
  }
  // PNG: trajectories, 2 error plots, junctions, matches, 2 wireframe views; JPEG: 3 match pictures.
  EXPECT_EQ(CheckEmbeddedImages(html, "png"), 7);
  EXPECT_EQ(CheckEmbeddedImages(html, "jpeg"), 3);
  // Nothing fetched: every src is a data: URI, no stylesheet link, no CSS url(). Three scripts: the
  // 3D view's scene, the import map that inlines three.js, the viewer.
  for (size_t at = html.find(" src="); at != std::string::npos; at = html.find(" src=", at + 1)) {
    EXPECT_EQ(html.compare(at, 11, " src=\"data:"), 0) << html.substr(at, 40);
  }
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("url("), std::string::npos);
  EXPECT_EQ(Count(html, "<script"), 3);
  EXPECT_NE(html.find("<script type=\"importmap\">"), std::string::npos);
  EXPECT_NE(html.find("<script type=\"module\">"), std::string::npos);
}

// The 3D view's scene JSON: the wireframe's points and edges, three paths, a frustum (8 segments)
// per camera; and the import map's data: URLs decode to the vendored three.js, the module build's
// import of its core renamed to the bare "three/core" (a data: URL cannot resolve "./").
TEST(ReportTest, The3dViewHoldsTheSceneAndTheInlinedThreeJs) {
  const HandBuiltRun run;
  const std::string html = ReportHtml(run.sequence, run.result, run.images);
  const std::string scene =
      Between(html, "<script type=\"application/json\" id=\"view3d-scene\">", "</script>");
  const Landmarks& drawn = run.result.wireframe_landmarks;
  EXPECT_EQ(Count(Between(scene, "\"points\":[", "]"), ",") + 1, 3 * int(drawn.points.size()));
  EXPECT_EQ(Count(Between(scene, "\"edges\":[", "]"), ",") + 1,
            6 * int(drawn.lines.size() + drawn.point_edges.size()));
  EXPECT_EQ(Count(scene, "\"name\":"), 3);  // ground truth, odometry, refined
  EXPECT_EQ(Count(Between(scene, "\"frusta\":{", "}"), ",") + 1, 1 + 8 * 6 * kFrames);

  const std::string map = Between(html, "<script type=\"importmap\">", "</script>");
  EXPECT_EQ(map.find('<'), std::string::npos);
  const std::string prefix = "data:text/javascript;charset=utf-8,";
  auto module = [&](const std::string& name) {
    return PercentDecoded(Between(map, "\"" + name + "\":\"" + prefix, "\""));
  };
  EXPECT_EQ(module("three/core"), report_assets::kThreeCore);
  EXPECT_EQ(module("three/addons/controls/OrbitControls.js"), report_assets::kOrbitControls);
  const std::string three = module("three");
  // "./three.core.min.js" (19 characters) twice replaced by "three/core" (10).
  EXPECT_EQ(three.size(), std::string(report_assets::kThreeModule).size() - 2 * 9);
  EXPECT_EQ(three.find("./three.core.min.js"), std::string::npos);
  EXPECT_EQ(Count(three, "from\"three/core\""), 2);
  EXPECT_NE(html.find(report_assets::kViewer), std::string::npos);
}

TEST(ReportTest, SaysSoWhenThereIsNoGroundTruthAndNoImage) {
  HandBuiltRun run;
  run.sequence.has_groundtruth = false;
  run.result.world_T_camera_truth.reset();
  run.result.drift_odometry.reset();
  run.result.drift_refined.reset();
  // No images given, and the sequence directory does not exist: the pictures are replaced by a note.
  const std::string html = ReportHtml(run.sequence, run.result, {});
  EXPECT_NE(html.find("no ground truth"), std::string::npos);
  EXPECT_EQ(html.find("position error per frame"), std::string::npos);
  EXPECT_NE(html.find("the image could not be read"), std::string::npos);
  // Trajectories, junctions, matches, 2 wireframe views; no match picture.
  EXPECT_EQ(CheckEmbeddedImages(html, "png"), 5);
  EXPECT_EQ(CheckEmbeddedImages(html, "jpeg"), 0);
}

TEST(ReportTest, EmptyResultStillGivesAPage) {
  HandBuiltRun run;
  PipelineResult empty;
  empty.world_T_camera_odometry = run.result.world_T_camera_odometry;
  const std::string html = ReportHtml(run.sequence, empty, {});
  EXPECT_NE(html.find("No consecutive pair of frames was matched"), std::string::npos);
  EXPECT_NE(html.find("no wireframe to show"), std::string::npos);
  EXPECT_EQ(CheckEmbeddedImages(html), 3);  // trajectories, junctions, matches (empty bars)
}

// Issue 18, item 4: 8000x6000 frames gave a 60 MB page that took 14 s to write, as the match
// pictures embedded the frames at full size. Frames of 4000x3000 (the hand-built run scaled 25
// times, with noise so PNG cannot compress it away) now give pictures at most 2 x 960 pixels wide
// and a page under 8 MB (at full size, 25 times the pixels, it would be above 100 MB), whether the
// frames are given undistorted or as stored.
TEST(ReportTest, MatchPicturesOfLargeFramesAreShrunk) {
  HandBuiltRun run;
  constexpr double kScale = 25;
  Camera& camera = run.sequence.calibration.camera;
  camera.width *= kScale, camera.height *= kScale, camera.fx *= kScale, camera.fy *= kScale;
  camera.cx = (camera.cx + 0.5) * kScale - 0.5, camera.cy = (camera.cy + 0.5) * kScale - 0.5;
  cv::RNG rng(7);
  for (cv::Mat& image : run.images) {
    cv::Mat large, noise(camera.height, camera.width, CV_8UC1);
    cv::resize(image, large, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_NEAREST);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 40);
    image = large + noise;
  }
  for (Junctions& junctions : run.result.junctions) {
    for (Junction& junction : junctions) {
      junction.location = (junction.location.array() + 0.5) * kScale - 0.5;
      for (JunctionSegment& segment : junction.segments)
        segment.end = (segment.end.array() + 0.5) * kScale - 0.5;
    }
  }
  for (const bool as_stored : {false, true}) {
    const std::string html = as_stored ? ReportHtml(run.sequence, run.result, {}, run.images)
                                       : ReportHtml(run.sequence, run.result, run.images);
    EXPECT_LT(html.size(), 8u << 20) << "as stored: " << as_stored;
    const std::string prefix = "data:image/jpeg;base64,";  // the match pictures
    int pictures = 0;
    for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at + 1)) {
      const size_t begin = at + prefix.size(), end = html.find('"', begin);
      std::string jpeg;
      ASSERT_TRUE(Base64Decode(html.substr(begin, end - begin), &jpeg));
      const cv::Mat image = cv::imdecode(std::vector<uchar>(jpeg.begin(), jpeg.end()), cv::IMREAD_UNCHANGED);
      EXPECT_LE(image.cols, 2 * 960 + 40);
      pictures += image.cols > 1000;
    }
    EXPECT_GE(pictures, 1) << "the match pictures are there";
  }
}

TEST(ReportTest, FailsWhenTheDirectoryCannotBeWritten) {
  const HandBuiltRun run;
  const std::string dir = testing::MakeScratchDir("report_unwritable");
  std::ofstream(dir + "/file") << "x";
  const Status status = WriteReport(run.sequence, run.result, run.images, dir + "/file/sub");
  EXPECT_FALSE(status.ok());
  EXPECT_FALSE(status.message().empty());
}

TEST(TrajectoryErrorsTest, RigidlyMovedTruthHasNoError) {
  const HandBuiltRun run;
  const std::vector<Pose3>& truth = *run.result.world_T_camera_truth;
  const Pose3 moved_T_world(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())),
                            Eigen::Vector3d(1, -2, 0));
  std::vector<Pose3> estimated;
  for (const Pose3& pose : truth) estimated.push_back(moved_T_world * pose);
  const TrajectoryErrors errors = ComputeTrajectoryErrors(estimated, truth, 2);
  ASSERT_EQ(errors.position_m.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(errors.position_m[i], 0, 1e-9);
    EXPECT_NEAR(errors.heading_rad[i], 0, 1e-9);
  }
}

TEST(TrajectoryErrorsTest, HeadingErrorIsTheYawOffsetAndPositionRmseIsTheAte) {
  const HandBuiltRun run;
  const std::vector<Pose3>& truth = *run.result.world_T_camera_truth;
  // Same positions, each camera turned 0.1 rad to the left about the vertical.
  std::vector<Pose3> turned;
  for (const Pose3& pose : truth) {
    turned.push_back(Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())) * pose.rotation,
                           pose.translation));
  }
  const TrajectoryErrors heading = ComputeTrajectoryErrors(turned, truth, 2);
  for (double e : heading.heading_rad) EXPECT_NEAR(e, 0.1, 1e-9);
  for (double e : heading.position_m) EXPECT_NEAR(e, 0, 1e-9);

  const TrajectoryErrors odometry = ComputeTrajectoryErrors(run.result.world_T_camera_odometry, truth, 2);
  double sum = 0;
  for (double e : odometry.position_m) sum += e * e;
  EXPECT_NEAR(std::sqrt(sum / odometry.position_m.size()), run.result.drift_odometry->ate_m, 1e-12);
  EXPECT_GT(run.result.drift_odometry->ate_m, 0.001);
}

// Up from the base frame (world z for a level robot whatever the camera's tilt; -z in a world
// turned upside down), or the cameras' -y where the rig is the identity. Tolerance 1e-12.
TEST(UpDirectionTest, FromTheBaseFrameOrTheUprightCamera) {
  // The generator's rig: camera looking along base x, tilted down 10 degrees, 1 m up.
  const Eigen::Matrix3d camera_axes_in_base =
      (Eigen::AngleAxisd(0.1745, Eigen::Vector3d::UnitY()).toRotationMatrix() *
       (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished());
  const Pose3 base_T_camera(Eigen::Quaterniond(camera_axes_in_base), Eigen::Vector3d(0.2, 0, 1));
  std::vector<Pose3> world_T_camera;
  for (int i = 0; i < 5; ++i) {
    const Pose3 world_T_base(Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitZ())),
                             Eigen::Vector3d(i, 0.5 * i, 0));
    world_T_camera.push_back(world_T_base * base_T_camera);
  }
  EXPECT_LT((UpDirection(world_T_camera, base_T_camera) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  const Pose3 flip(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())),
                   Eigen::Vector3d::Zero());
  std::vector<Pose3> flipped;
  for (const Pose3& pose : world_T_camera) flipped.push_back(flip * pose);
  EXPECT_LT((UpDirection(flipped, base_T_camera) + Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // Camera poses given directly: an upright camera looking along world y has -y_camera = world z.
  const Pose3 upright(Eigen::Quaterniond((Eigen::Matrix3d() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished()),
                      Eigen::Vector3d(1, 2, 3));
  EXPECT_LT((UpDirection({upright}, Pose3()) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_EQ(UpDirection({}, base_T_camera), Eigen::Vector3d::UnitZ());
}

TEST(VerticalAxisTest, FloorPlaneAndOtherPlanes) {
  std::vector<Pose3> floor, xz;
  for (int i = 0; i < 10; ++i) {
    floor.push_back(Pose3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.3 * i, std::sin(i), 0.01 * (i % 2))));
    xz.push_back(Pose3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.3 * i, 1.5, std::sin(i))));
  }
  EXPECT_EQ(VerticalAxis(floor), 2);
  EXPECT_EQ(VerticalAxis(xz), 1);
  EXPECT_EQ(VerticalAxis({}), 2);
}

}  // namespace
}  // namespace sfm

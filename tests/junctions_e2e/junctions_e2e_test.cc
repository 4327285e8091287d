// End to end on one generated frame: render a small scene with the generator library (fixed noise
// seed), detect segments and junctions, and compare with the frame's true vertices
// (docs/junction_results.md gives the definitions and the full benchmark).
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "frontend/junctions/junction_detector.h"
#include "frontend/segments/segment_detector.h"
#include "benchmarks/evaluation/segment_evaluation.h"
#include "sequences/generator/camera_rig.h"
#include "sequences/generator/renderer.h"
#include "sequences/generator/visibility.h"
#include "sequences/generator/wireframe.h"
#include "benchmarks/evaluation/junction_evaluation.h"
#include "tests/test_scenes.h"

namespace sfm {
namespace {

// A 6 x 4 x 2.5 m room with three boxes on the floor and a poster, built by hand (not by the
// random scene builder, so the frame stays the same while the builder changes).
Scene SmallScene() {
  Scene scene = testing::RoomShell(6, 4, /*height=*/2.5);
  scene.AddBox(scene.AddObject("box", true), {3.2, 1.3}, 0.35, 0, {0.7, 0.5, 0.6}, 0.25, false);
  scene.AddBox(scene.AddObject("box", true), {4.3, 2.7}, -0.6, 0, {0.6, 0.6, 1.1}, 0.5, false);
  scene.AddBox(scene.AddObject("box", true), {2.6, 2.9}, 0.1, 0, {0.5, 0.4, 0.4}, 0.15, false);
  // A poster on the far wall (x = 6), facing the room.
  const double x = 5.999;
  scene.AddPolygon(scene.AddObject("poster"),
                   {{x, 1.2, 1.1}, {x, 2.2, 1.1}, {x, 2.2, 1.9}, {x, 1.2, 1.9}}, 0.2, -Eigen::Vector3d::UnitX());
  return scene;
}

struct FrameResult {
  int detectable = 0, found = 0;
  double median_error = 0;
};

FrameResult RunFrame(SegmentMethod method) {
  const Scene scene = SmallScene();
  const Wireframe wireframe = ExtractWireframe(scene);
  const CameraRigOptions rig;  // 640 x 480, fx = fy = 450, 1 m high, pitched 0.05 rad down
  const Camera camera = rig.MakeCamera();
  // Robot at (0.8, 1.8) on the floor, heading along +x and 0.15 rad to the left.
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Pose3 world_T_camera = Pose3(yaw, Eigen::Vector3d(0.8, 1.8, 0)) * rig.BaseTCamera();

  const Renderer renderer(scene, camera, RenderOptions());  // supersampled, blur 0.7 px, noise 2 grey levels
  Canvas canvas;
  const cv::Mat image = renderer.Render(world_T_camera, /*noise_seed=*/17, &canvas);
  FrameTruth truth;
  ComputeFrameTruth(scene, wireframe, camera, world_T_camera, canvas, VisibilityOptions(), &truth);
  const FrameTrueJunctions true_junctions = TrueJunctionsOfFrame(wireframe, truth, TrueJunctionOptions());

  SegmentDetectorOptions segment_options;
  segment_options.method = method;
  const Junctions junctions = DetectJunctions(DetectLineSegments(image, segment_options), JunctionDetectorOptions());

  std::vector<Eigen::Vector2d> detectable, detected;
  for (const TrueVertexJunction& v : true_junctions.vertices) {
    if (v.detectable) detectable.push_back(v.location);
  }
  for (const Junction& j : junctions) detected.push_back(j.location);
  FrameResult result;
  result.detectable = static_cast<int>(detectable.size());
  std::vector<double> errors;
  for (const PointMatch& match : MatchPoints(detectable, detected, 3.0)) errors.push_back(match.distance);
  result.found = static_cast<int>(errors.size());
  result.median_error = Quantile(errors, 0.5);
  std::printf("%s segments: %d of %d detectable vertices within 3 px, median error %.3f px, %zu junctions\n",
              method == SegmentMethod::kFast ? "fast" : "reference", result.found, result.detectable,
              result.median_error, junctions.size());
  return result;
}

// Measured when written: 25 detectable vertices; found within 3 px 22 with fast segments (88 %,
// median error 0.11 px) and 23 with reference segments (92 %, 0.08 px); the three misses were corners
// of the dark box's top face, whose edges with its sides are of low contrast. Since the NFA counts
// chain sub-runs (commit 2db1a25) and the end-point model and threshold are the fitted ones, both
// found all 25 (median 0.15 / 0.08 px); since the fast path's corner changes (commit 9567318) the
// fast segments find 24 (median 0.10 px; the miss, an L of 17 degrees, is in
// docs/junction_results.md), the reference 25 (0.08 px). The floor, 88 % (22 of 25), tolerates three misses from
// changes in the segment detector; the median error must stay below the benchmark's goal of 0.7 px.
constexpr double kRecallFloor = 0.88;
constexpr double kMaxMedianError = 0.7;  // px

TEST(JunctionsEndToEndTest, GeneratedFrameFastSegments) {
  const FrameResult r = RunFrame(SegmentMethod::kFast);
  ASSERT_GE(r.detectable, 20) << "the scene should show at least 20 detectable vertices";
  EXPECT_GE(static_cast<double>(r.found) / r.detectable, kRecallFloor);
  EXPECT_LT(r.median_error, kMaxMedianError);
}

TEST(JunctionsEndToEndTest, GeneratedFrameReferenceSegments) {
  const FrameResult r = RunFrame(SegmentMethod::kReference);
  ASSERT_GE(r.detectable, 20) << "the scene should show at least 20 detectable vertices";
  EXPECT_GE(static_cast<double>(r.found) / r.detectable, kRecallFloor);
  EXPECT_LT(r.median_error, kMaxMedianError);
}

}  // namespace
}  // namespace sfm

// End to end on consecutive generated frames: render a small hand-built room with the generator
// library (fixed noise seeds), detect segments, junctions and topology graphs, match with F from
// seeded noisy odometry, and score against the true vertices (docs/matching_results.md gives the
// definitions and the full benchmark).
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/epipolar.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/segments/segment_detector.h"
#include "sequences/generator/camera_rig.h"
#include "sequences/generator/odometry_noise.h"
#include "sequences/generator/renderer.h"
#include "sequences/generator/visibility.h"
#include "sequences/generator/wireframe.h"
#include "benchmarks/evaluation/matching_evaluation.h"
#include "tests/test_scenes.h"

namespace sfm {
namespace {

// A 7 x 4 x 2.5 m room with boxes (two of them stacked), a cabinet and posters, built by hand (not
// by the random scene builder, so the frames stay the same while the builder changes).
Scene SmallRoom() {
  Scene scene = testing::RoomShell(7, 4, /*height=*/2.5);
  scene.AddBox(scene.AddObject("box", true), {3.6, 1.2}, 0.35, 0, {0.7, 0.5, 0.6}, 0.25, false);
  scene.AddBox(scene.AddObject("box", true), {4.8, 2.8}, -0.6, 0, {0.6, 0.6, 1.1}, 0.5, false);
  scene.AddBox(scene.AddObject("box", true), {3.0, 3.0}, 0.1, 0, {0.5, 0.4, 0.4}, 0.15, false);
  scene.AddBox(scene.AddObject("box", true), {3.0, 3.0}, -0.3, 0.4, {0.3, 0.3, 0.3}, 0.55, true);
  scene.AddBox(scene.AddObject("cabinet", true), {6.6, 0.6}, 0, 0, {0.7, 0.5, 1.8}, 0.45, false);
  scene.AddBox(scene.AddObject("box", true), {5.6, 1.6}, 0.8, 0, {0.4, 0.4, 0.5}, 0.8, false);
  // Posters: two on the far wall (x = 7), one on the left wall (y = 4), facing the room.
  const double x = 6.995, y = 3.995;
  scene.AddPolygon(scene.AddObject("poster"), {{x, 1.4, 1.1}, {x, 2.4, 1.1}, {x, 2.4, 1.9}, {x, 1.4, 1.9}}, 0.2,
                   -Eigen::Vector3d::UnitX());
  scene.AddPolygon(scene.AddObject("poster"), {{x, 2.8, 0.9}, {x, 3.5, 0.9}, {x, 3.5, 1.6}, {x, 2.8, 1.6}}, 0.95,
                   -Eigen::Vector3d::UnitX());
  scene.AddPolygon(scene.AddObject("poster"), {{2.0, y, 1.0}, {3.2, y, 1.0}, {3.2, y, 1.8}, {2.0, y, 1.8}}, 0.25,
                   -Eigen::Vector3d::UnitY());
  return scene;
}


// Frames along a gentle left turn, 0.2 m apart; each consecutive pair matched under the odometry F.
VertexMatchCounts RunFrames(int num_frames, bool print) {
  const Scene scene = SmallRoom();
  const Wireframe wireframe = ExtractWireframe(scene);
  const CameraRigOptions rig;  // 640 x 480, fx = fy = 450, 1 m high, pitched 0.05 rad down
  const Camera camera = rig.MakeCamera();
  std::vector<Pose3> world_T_base;
  for (int i = 0; i < num_frames; ++i) {
    const double yaw = 0.05 + 0.03 * i;
    world_T_base.emplace_back(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                              Eigen::Vector3d(0.8 + 0.2 * i, 1.7 + 0.2 * i * std::sin(yaw), 0));
  }
  // The generator's default wheel-odometry noise (2 % scale, 1 % distance, 0.002 rad heading
  // jitter, 0.001 rad/frame heading bias), seed 5.
  const std::vector<Pose3> odometry = SimulateOdometry(world_T_base, OdometryNoiseOptions(), /*seed=*/5);

  const Renderer renderer(scene, camera, RenderOptions());  // supersampled, blur 0.7 px, noise 2 grey levels
  const MatchingOptions matching;  // the defaults
  std::vector<FrameFeatures> features;
  std::vector<FrameTruth> truths;
  for (int i = 0; i < num_frames; ++i) {
    const Pose3 world_T_camera = world_T_base[i] * rig.BaseTCamera();
    Canvas canvas;
    const cv::Mat image = renderer.Render(world_T_camera, /*noise_seed=*/100 + i, &canvas);
    FrameTruth truth;
    ComputeFrameTruth(scene, wireframe, camera, world_T_camera, canvas, VisibilityOptions(), &truth);
    truths.push_back(truth);
    features.push_back(DetectFrameFeatures(image, SegmentDetectorOptions(), JunctionDetectorOptions()));
  }
  VertexMatchCounts total;
  for (int i = 0; i + 1 < num_frames; ++i) {
    // As the pipeline: the odometry pose with the noise model sequence.yaml would state.
    const OdometryNoise noise = OdometryNoiseOptions().ForCalibration();
    const PairGeometry geometry =
        PairGeometryFromOdometry(camera.K(), rig.BaseTCamera(), odometry[i], odometry[i + 1],
                                 noise.translation_sigma, noise.rotation_sigma, /*frames_apart=*/1);
    const Eigen::Matrix3d F = geometry.Fundamental();
    const std::vector<JunctionMatch> matches = MatchJunctions(
        features[i].junctions, features[i].graph, features[i + 1].junctions, features[i + 1].graph, geometry, matching);
    const VertexMatchCounts c = ScoreVertexMatches(
        features[i].junctions, features[i + 1].junctions, TrueVerticesNearJunctions(features[i].junctions, truths[i], 3.0),
        TrueVerticesNearJunctions(features[i + 1].junctions, truths[i + 1], 3.0), matches, F, matching, &geometry);
    if (print) {
      std::printf("pair %d-%d: %zu and %zu junctions, %d matches, %d at vertices, %d same vertex; %d vertices in both, "
                  "%d matched\n",
                  i, i + 1, features[i].junctions.size(), features[i + 1].junctions.size(), c.matches, c.associated,
                  c.same_vertex, c.seen_both, c.matched);
    }
    total.Add(c);
    if (print) {
      const auto near_a = TrueVerticesNearJunctions(features[i].junctions, truths[i], 3.0);
      const auto near_b = TrueVerticesNearJunctions(features[i + 1].junctions, truths[i + 1], 3.0);
      for (const JunctionMatch& m : matches) {
        if (SameTrueVertex(near_a[m.index_a], near_b[m.index_b]) != 0) continue;
        const Junction& ja = features[i].junctions[m.index_a];
        const Junction& jb = features[i + 1].junctions[m.index_b];
        std::printf("  wrong: (%.1f, %.1f) %s vertex %d -> (%.1f, %.1f) %s vertex %d, similarity %.3f\n",
                    ja.location.x(), ja.location.y(), JunctionTypeName(ja.type), near_a[m.index_a][0],
                    jb.location.x(), jb.location.y(), JunctionTypeName(jb.type), near_b[m.index_b][0], m.similarity);
      }
    }
  }
  return total;
}

// Measured (defaults: tau1 = 0, tau2 = 0.1, linear rho1, sigma, the pose band and cheirality, and
// the geometric verification with its guided pass; segments and junctions at commit 9567318), three
// pairs: 105 matches, 85 with both junctions within 3 px of true vertices, all 85 at the same
// vertex (100 %); 96 vertices seen in both frames, 85 matched (88.5 %). Without the verification
// (refine_geometry = false) the same 85 of 85 and 85 of 96, from 113 matches: on this scene the
// segment detector of 9567318 already removed the one wrong match; the verification drops 8 more
// matches, none of them between junctions at true vertices. Before the guided pass (commit b1f35d1, detection
// of a43b270): 87 of 88 (98.9 %) and 87 of 97; with the fixed R = 10 px and no cheirality (740514a):
// 87 of 89 and 87 of 97. The floors allow two more wrong matches (95 %) and seven more misses
// (80 %); PrecisionGoal checks the 99 %, which one wrong match of 85 would miss.
constexpr int kNumFrames = 4;
constexpr int kMinAssociated = 60;        // matches with both junctions at true vertices, at least
constexpr double kPrecisionFloor = 0.95;  // measured 1.000
constexpr double kRecallFloor = 0.80;     // measured 0.885
constexpr double kPrecisionGoal = 0.99;   // issue 4

TEST(MatchingEndToEndTest, ConsecutiveGeneratedFramesWithOdometryF) {
  const VertexMatchCounts c = RunFrames(kNumFrames, /*print=*/true);
  ASSERT_GE(c.associated, kMinAssociated) << "the scene should give enough matches at true vertices";
  EXPECT_GE(static_cast<double>(c.same_vertex) / c.associated, kPrecisionFloor)
      << c.associated - c.same_vertex << " of " << c.associated << " matches at true vertices pair different vertices";
  EXPECT_GE(static_cast<double>(c.matched) / c.seen_both, kRecallFloor)
      << c.matched << " of " << c.seen_both << " vertices seen in both frames matched";
}

// The goal (measured 85 of 85, with and without the geometric verification, at 9567318).
TEST(MatchingEndToEndTest, PrecisionGoal) {
  const VertexMatchCounts c = RunFrames(kNumFrames, /*print=*/false);
  ASSERT_GE(c.associated, kMinAssociated);
  EXPECT_GE(static_cast<double>(c.same_vertex) / c.associated, kPrecisionGoal);
}

}  // namespace
}  // namespace sfm

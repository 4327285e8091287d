// The README's headline figures, held by ctest on the default pipeline (issue 16 item 6; label
// `benchmark`): a generated room loop and a generated corridor, 40 frames each with the generator's
// default odometry noise, run through RunPipeline with default options. Per sequence:
// - refined ATE ratio: the README has 0.03-0.08 of the odometry's ATE on the benchmark's generated
//   sequences and at most 0.16 on held-out ones; asserted <= 0.2 (issue 5's goal);
// - wireframe precision: the share of wireframe.ply's vertices within 5 cm of a true edge
//   (evaluate_wireframe's "share", no alignment); README 93.5-98.4 %; asserted >= 0.90;
// - matching precision: of the pipeline's matches whose two junctions each lie within 3 px of a
//   visible true vertex, the share at one same vertex (benchmark_matching's generated precision,
//   ScoreVertexMatches' same_vertex / associated); README 99.3-99.7 %; asserted >= 0.98.
// Measured with the initial trajectory from the images (ratio / wireframe share / matching
// precision): room loop 0.079 / 0.986 / 0.9947, corridor 0.037 / 0.974 / 0.9923; about 5 s of processor time in all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "backend/export/ply_io.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/sequence_writer.h"
#include "benchmarks/evaluation/matching_evaluation.h"
#include "pipeline/pipeline.h"
#include "tests/test_data.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

constexpr double kMaxAteRatio = 0.2;            // refined ATE / odometry ATE, at most
constexpr double kWireframeThresholdM = 0.05;   // a vertex on a true edge within this
constexpr double kMinWireframeShare = 0.90;     // of wireframe.ply's vertices, at least
constexpr double kVertexRadiusPx = 3.0;         // a junction at a true vertex within this
constexpr double kMinMatchingPrecision = 0.98;  // of the matches both at true vertices, at least
constexpr int kFrames = 40;

struct HeadlineFigures {
  double ate_odometry = 0, ate_refined = 0;
  int wireframe_vertices = 0, wireframe_within = 0;
  int matches_at_vertices = 0, matches_same_vertex = 0;
  int loops_closed = 0;
};

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Generates the sequence, runs the default pipeline and measures its outputs against the truth.
HeadlineFigures Measure(const std::string& name, SceneType scene, TrajectoryType trajectory,
                        std::uint64_t seed, double odometry_noise_scale = 1, int frames = kFrames) {
  HeadlineFigures figures;
  const fs::path scratch = testing::MakeScratchDir(name);
  const std::string sequence_dir = (scratch / "sequence").string(),
                    output_dir = (scratch / "output").string();
  GeneratorOptions generator;
  generator.scene.type = scene;
  generator.trajectory.type = trajectory;
  generator.trajectory.num_frames = frames;
  generator.seed = seed;
  generator.odometry = generator.odometry.Scaled(odometry_noise_scale);
  Status status = GenerateSequence(generator, sequence_dir, /*overwrite=*/true);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok()) return figures;

  PipelineOptions options;
  options.sequence_dir = sequence_dir;
  options.output_dir = output_dir;
  options.show_progress = false;
  PipelineResult result;
  status = RunPipeline(options, &result);
  EXPECT_TRUE(status.ok()) << status.message();
  if (!status.ok() || !result.drift_odometry || !result.drift_refined) {
    ADD_FAILURE() << name << ": no drift figures (the sequence has ground truth)";
    return figures;
  }
  figures.ate_odometry = result.drift_odometry->ate_m;
  figures.ate_refined = result.drift_refined->ate_m;
  figures.loops_closed = static_cast<int>(result.initialization.loops.size());

  GroundTruth truth;
  status = ReadGroundTruth(sequence_dir, &truth);
  EXPECT_TRUE(status.ok()) << status.message();
  ReconstructedWireframe wireframe;
  const Status read = ReadPly((fs::path(output_dir) / "wireframe.ply").string(), &wireframe);
  EXPECT_TRUE(read.ok()) << read.message();
  if (!status.ok() || !read.ok()) return figures;
  figures.wireframe_vertices = static_cast<int>(wireframe.vertices.size());
  for (const Eigen::Vector3d& p : wireframe.vertices) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const WireEdge& edge : truth.wireframe.edges) {
      nearest = std::min(nearest, DistanceToSegment(p, truth.wireframe.vertices[edge.vertex_a],
                                                    truth.wireframe.vertices[edge.vertex_b]));
    }
    figures.wireframe_within += nearest <= kWireframeThresholdM;
  }

  // The generator has no lens distortion by default, so the pipeline's junctions and the truth's
  // projected vertices share one pixel frame.
  std::vector<std::vector<std::vector<int>>> near(result.junctions.size());
  for (size_t f = 0; f < result.junctions.size() && f < truth.frames.size(); ++f) {
    near[f] = TrueVerticesNearJunctions(result.junctions[f], truth.frames[f], kVertexRadiusPx);
  }
  for (const FramePairMatches& pair : result.pairs) {
    for (const auto& [a, b] : MatchPairs(pair.matches)) {
      const int same = SameTrueVertex(near[pair.frame_a][a], near[pair.frame_b][b]);
      if (same < 0) continue;
      ++figures.matches_at_vertices;
      figures.matches_same_vertex += same;
    }
  }
  return figures;
}

void ExpectHeadlineFigures(const HeadlineFigures& f) {
  ASSERT_GT(f.ate_odometry, 0);
  ASSERT_GT(f.wireframe_vertices, 100);
  ASSERT_GT(f.matches_at_vertices, 1000);
  const double ratio = f.ate_refined / f.ate_odometry;
  const double share = static_cast<double>(f.wireframe_within) / f.wireframe_vertices;
  const double precision = static_cast<double>(f.matches_same_vertex) / f.matches_at_vertices;
  EXPECT_LE(ratio, kMaxAteRatio) << "refined ATE " << f.ate_refined << " m, odometry " << f.ate_odometry
                                 << " m";
  EXPECT_GE(share, kMinWireframeShare) << f.wireframe_within << " of " << f.wireframe_vertices << " vertices";
  EXPECT_GE(precision, kMinMatchingPrecision) << f.matches_same_vertex << " of " << f.matches_at_vertices;
  std::printf(
      "ATE ratio %.3f (%.4f / %.4f m), wireframe within 5 cm %.3f (%d / %d), matching precision %.4f "
      "(%d / %d)\n",
      ratio, f.ate_refined, f.ate_odometry, share, f.wireframe_within, f.wireframe_vertices, precision,
      f.matches_same_vertex, f.matches_at_vertices);
}

TEST(HeadlineFiguresTest, RoomLoop) {
  ExpectHeadlineFigures(Measure("benchmark_room_loop", SceneType::kRoom, TrajectoryType::kLoop, /*seed=*/1));
}

TEST(HeadlineFiguresTest, Corridor) {
  ExpectHeadlineFigures(
      Measure("benchmark_corridor", SceneType::kCorridor, TrajectoryType::kStraight, /*seed=*/1));
}

}  // namespace
}  // namespace sfm

namespace sfm {
namespace {

// Issue 17: the images lead when the odometry is poor. A room loop with every odometry noise term
// 6x the generator's default (12 % scale error, 6 % distance noise, 0.012 rad heading noise and
// 0.006 rad heading bias per frame); asserted: refined ATE at most 0.3 of the odometry's (the
// issue's figure). Measured when the test was written: 0.031 (0.0041 / 0.1331 m).
TEST(HeadlineFiguresTest, RoomLoopWithSixTimesTheOdometryNoise) {
  const HeadlineFigures f =
      Measure("benchmark_room_loop_6x", SceneType::kRoom, TrajectoryType::kLoop, /*seed=*/1, /*scale=*/6);
  ASSERT_GT(f.ate_odometry, 0);
  EXPECT_LE(f.ate_refined / f.ate_odometry, 0.3) << "refined ATE " << f.ate_refined << " m, odometry "
                                                  << f.ate_odometry << " m";
  std::printf("6x: ATE ratio %.3f (%.4f / %.4f m)\n", f.ate_refined / f.ate_odometry, f.ate_refined,
              f.ate_odometry);
}

}  // namespace
}  // namespace sfm

namespace sfm {
namespace {

// Loop closure (docs/initialization.md, "Loop closure"): a room loop of 120 frames, one and a half
// laps, every odometry noise term 3x the default, seed 3. Without loop closure the second lap
// built its own tracks of the same corners on a drifted trajectory: refined ATE ratio 0.074 and
// wireframe within 5 cm 0.37. Asserted: at least one loop closed, ratio at most 0.05 and within
// 5 cm at least 0.9. Measured when the test was written: 3 loops, 0.014, 0.99.
TEST(HeadlineFiguresTest, RoomLoopOfOneAndAHalfLapsClosesItsLoop) {
  const HeadlineFigures f = Measure("benchmark_room_loop_laps", SceneType::kRoom, TrajectoryType::kLoop,
                                    /*seed=*/3, /*scale=*/3, /*frames=*/120);
  ASSERT_GT(f.ate_odometry, 0);
  ASSERT_GT(f.wireframe_vertices, 0);
  const double share = static_cast<double>(f.wireframe_within) / f.wireframe_vertices;
  EXPECT_GE(f.loops_closed, 1);
  EXPECT_LE(f.ate_refined / f.ate_odometry, 0.05);
  EXPECT_GE(share, 0.9);
  std::printf("1.5 laps at 3x: %d loops, ATE ratio %.3f (%.4f / %.4f m), within 5 cm %.3f\n", f.loops_closed,
              f.ate_refined / f.ate_odometry, f.ate_refined, f.ate_odometry, share);
}

}  // namespace
}  // namespace sfm

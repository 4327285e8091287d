// The whole pipeline on a generated sequence with known truth: every SPEC section 3 output is
// written and readable, and the bundle adjustment improves on the odometry.
#include "pipeline/pipeline.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "backend/export/ply_io.h"
#include "frontend/junctions/junctions_json.h"
#include "geometry/tum_io.h"
#include "sequences/generator/sequence_writer.h"
#include "tests/test_data.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;

// The generator's room loop, seed 7, of num_frames frames: the sequences these tests run on.
GeneratorOptions RoomLoop(int num_frames) {
  GeneratorOptions generator;
  generator.scene.type = SceneType::kRoom;
  generator.trajectory.type = TrajectoryType::kLoop;
  generator.trajectory.num_frames = num_frames;
  generator.seed = 7;
  return generator;
}
using ::testing::HasSubstr;
using ::testing::StartsWith;

using testing::ReadFile;

class PipelineOnGeneratedRoom : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path scratch = testing::MakeScratchDir("pipeline_room");
    sequence_dir_ = (scratch / "sequence").string();
    output_dir_ = (scratch / "output").string();
    GeneratorOptions generator = RoomLoop(30);
    generator.odometry.heading_bias = 0.004;  // rad per frame: a drift the bundle adjustment must remove
    ASSERT_TRUE(GenerateSequence(generator, sequence_dir_, /*overwrite=*/true).ok());
    PipelineOptions options;
    options.sequence_dir = sequence_dir_;
    options.output_dir = output_dir_;
    options.show_progress = false;
    const Status status = RunPipeline(options, &result_);
    ASSERT_TRUE(status.ok()) << status.message();
  }

  static std::string sequence_dir_, output_dir_;
  static PipelineResult result_;
};

std::string PipelineOnGeneratedRoom::sequence_dir_;
std::string PipelineOnGeneratedRoom::output_dir_;
PipelineResult PipelineOnGeneratedRoom::result_;

TEST_F(PipelineOnGeneratedRoom, WritesEveryJunctionFileInTheSpecShape) {
  const fs::path out(output_dir_);
  for (int frame = 0; frame < 30; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.json", frame);
    JunctionsFile file;
    const Status status = JunctionsFromJson(ReadFile(out / "junctions" / name), name, &file);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(file.frame, frame);
    EXPECT_EQ(file.width, 640);
    EXPECT_FALSE(file.junctions.empty()) << name;
  }
}

TEST_F(PipelineOnGeneratedRoom, WritesMatchesTracksAndTrajectories) {
  const fs::path out(output_dir_);
  for (int frame = 0; frame + 1 < 30; ++frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06d_%06d.csv", frame, frame + 1);
    EXPECT_THAT(ReadFile(out / "matches" / name), StartsWith("id_a,id_b,similarity\n")) << name;
  }
  EXPECT_THAT(ReadFile(out / "tracks.csv"), StartsWith("track_id,frame,junction_id\n"));
  for (const char* name : {"trajectory_odometry.txt", "trajectory_refined.txt", "trajectory_groundtruth.txt"}) {
    std::vector<StampedPose> poses;
    ASSERT_TRUE(ReadTumTrajectory((out / name).string(), &poses).ok()) << name;
    EXPECT_EQ(poses.size(), 30u) << name;
  }
}

TEST_F(PipelineOnGeneratedRoom, WritesWireframeColmapModelAndEveryMetricsKey) {
  const fs::path out(output_dir_);
  ReconstructedWireframe wireframe;
  ASSERT_TRUE(ReadPly((out / "wireframe.ply").string(), &wireframe).ok());
  EXPECT_GT(wireframe.vertices.size(), 20u);
  EXPECT_GT(wireframe.edges.size(), 10u);
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt"}) {
    EXPECT_TRUE(fs::exists(out / "colmap" / name)) << name;
  }
  // Every 3D point vertex names its track: in tracks.csv, and COLMAP's point track_id + 1 at the
  // same position (bit for bit). The edges between points (topology edges) are written.
  ASSERT_EQ(wireframe.track_ids.size(), wireframe.vertices.size());
  std::set<int> tracks;
  std::istringstream tracks_csv(ReadFile(out / "tracks.csv"));
  std::string line;
  std::getline(tracks_csv, line);
  while (std::getline(tracks_csv, line)) tracks.insert(std::stoi(line.substr(0, line.find(','))));
  std::map<long, Eigen::Vector3d> colmap_points;
  std::istringstream points3d(ReadFile(out / "colmap" / "points3D.txt"));
  while (std::getline(points3d, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    long id = 0;
    Eigen::Vector3d x;
    words >> id >> x.x() >> x.y() >> x.z();
    colmap_points[id] = x;
  }
  int with_track = 0;
  for (size_t v = 0; v < wireframe.vertices.size(); ++v) {
    const int track = wireframe.track_ids[v];
    if (track < 0) continue;
    ++with_track;
    EXPECT_TRUE(tracks.count(track)) << "vertex " << v << " track " << track;
    ASSERT_TRUE(colmap_points.count(track + 1)) << "vertex " << v << " track " << track;
    EXPECT_EQ(colmap_points[track + 1], wireframe.vertices[v]) << "vertex " << v;
  }
  EXPECT_GT(with_track, 20);
  EXPECT_GT(result_.wireframe_landmarks.point_edges.size(), 10u);
  const std::string metrics = ReadFile(out / "metrics.json");
  for (const char* key :
       {"frames", "junctions_per_frame", "matches_per_pair", "tracks", "points3d", "lines3d",
        "ate_odometry_m", "ate_refined_m", "rpe_odometry", "rpe_refined", "time_s", "ate_sim3_odometry_m",
        "ate_sim3_refined_m", "sim3_scale_odometry", "sim3_scale_refined"}) {
    EXPECT_THAT(metrics, HasSubstr(std::string("\"") + key + "\": ")) << key;
  }
}

// Figures protected: with a heading drift of 0.004 rad/frame (and the generator's 2 % scale
// error, which no monocular adjustment can see), the refined rotation RPE is at most half the
// odometry's, and the refined ATE is below the odometry's.
TEST_F(PipelineOnGeneratedRoom, BundleAdjustmentHalvesRotationDriftAndLowersAte) {
  ASSERT_TRUE(result_.drift_odometry && result_.drift_refined);
  EXPECT_LT(result_.drift_refined->rpe_rot_rad, 0.5 * result_.drift_odometry->rpe_rot_rad);
  EXPECT_LT(result_.drift_refined->ate_m, result_.drift_odometry->ate_m);
  RecordProperty("ate_odometry_m", std::to_string(result_.drift_odometry->ate_m));
  RecordProperty("ate_refined_m", std::to_string(result_.drift_refined->ate_m));
}

// Partial junction matches (an L in one frame against a Y in the other) go through the whole run:
// tracks join them through their common segments (the missing one is -1 in that view), lines are
// triangulated from the views that have the segment, and the report's match pictures draw them.
TEST(PipelineWithPartialMatches, CarriesThemIntoTracksLinesAndTheReport) {
  const fs::path scratch = testing::MakeScratchDir("pipeline_partial");
  const GeneratorOptions generator = RoomLoop(12);
  ASSERT_TRUE(GenerateSequence(generator, (scratch / "sequence").string(), /*overwrite=*/true).ok());
  PipelineOptions options;
  options.sequence_dir = (scratch / "sequence").string();
  options.output_dir = (scratch / "output").string();
  options.show_progress = false;
  PipelineResult result;
  const Status status = RunPipeline(options, &result);
  ASSERT_TRUE(status.ok()) << status.message();

  int partial_matches = 0;
  for (const FramePairMatches& pair : result.pairs) {
    for (const JunctionMatch& match : pair.matches) partial_matches += match.Partial();
  }
  EXPECT_GT(partial_matches, 0);
  int views_without_a_segment = 0;
  for (const JunctionTrack& track : result.tracks) {
    for (const TrackView& view : track.views) {
      ASSERT_EQ(static_cast<int>(view.segments.size()), track.NumSegments());
      views_without_a_segment += std::count(view.segments.begin(), view.segments.end(), -1) > 0;
    }
  }
  EXPECT_GT(views_without_a_segment, 0);
  EXPECT_FALSE(result.landmarks.lines.empty());
  for (const LineLandmark& line : result.landmarks.lines) {
    for (const LineObservation& observation : line.observations) EXPECT_GE(observation.segment, 0);
  }
  EXPECT_TRUE(fs::exists(fs::path(options.output_dir) / "report.html"));
}

// The parallel loops (frames, pairs, per-pair poses, lines on fixed poses) write each item into its
// own slot and sum in index order: one thread and two give the same bytes in every output the
// trajectory, the tracks and the wireframe come from (tolerance: none).
TEST(PipelineThreads, OneAndTwoThreadsWriteTheSameBytes) {
  const fs::path scratch = testing::MakeScratchDir("pipeline_threads");
  const GeneratorOptions generator = RoomLoop(24);
  ASSERT_TRUE(GenerateSequence(generator, (scratch / "sequence").string(), /*overwrite=*/true).ok());
  for (int threads : {1, 2}) {
    PipelineOptions options;
    options.sequence_dir = (scratch / "sequence").string();
    options.output_dir = (scratch / ("threads" + std::to_string(threads))).string();
    options.show_progress = false;
    options.threads = threads;
    const Status status = RunPipeline(options);
    ASSERT_TRUE(status.ok()) << status.message();
  }
  std::vector<std::string> names = {"trajectory_refined.txt", "tracks.csv", "wireframe.ply"};
  for (const auto& entry : fs::directory_iterator(scratch / "threads1" / "matches")) {
    names.push_back("matches/" + entry.path().filename().string());
  }
  EXPECT_GT(names.size(), 3u + 24);
  for (const std::string& name : names) {
    const std::string one = ReadFile(scratch / "threads1" / name);
    EXPECT_FALSE(one.empty()) << name;
    EXPECT_TRUE(one == ReadFile(scratch / "threads2" / name)) << name << " differs between 1 and 2 threads";
  }
}

}  // namespace
}  // namespace sfm

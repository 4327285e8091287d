#include "sfm_app/pipeline.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include <glog/logging.h>
#include <opencv2/core.hpp>

#include "frontend/geometry/epipolar.h"
#include "frontend/geometry/image_undistorter.h"
#include "frontend/geometry/tum_io.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/junctions_json.h"
#include "frontend/junctions/topology.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/sequence/sequence.h"
#include "frontend/util/atomic_file.h"
#include "frontend/util/json_format.h"
#include "frontend/util/progress.h"

namespace sfm {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct FrameFeatures {
  LineSegments segments;
  Junctions junctions;
  TopologyGraph graph;
};

struct PairMatches {
  int frame_a = 0, frame_b = 0;
  std::vector<JunctionMatch> matches;
};

struct StageTimes {
  double frontend = 0, matching = 0, backend = 0, total = 0;
};

// Everything the outputs are made from.
struct RunResult {
  std::vector<FrameFeatures> features;
  std::vector<PairMatches> pairs;
  StageTimes times;
};

Status LoadImages(const Sequence& sequence, Progress* progress, std::vector<cv::Mat>* images) {
  const int n = static_cast<int>(sequence.frames.size());
  images->resize(n);
  for (int i = 0; i < n; ++i) {
    progress->Update("reading images", "frame", i + 1, n);
    SFM_RETURN_IF_ERROR(LoadFrameImage(sequence, i, &(*images)[i]));
  }
  progress->Finish();
  return Status::Ok();
}

// Paper section 2: segments, junctions and the topology graph of every frame, in undistorted pixels.
std::vector<FrameFeatures> DetectFeatures(const Sequence& sequence, const std::vector<cv::Mat>& images,
                                          const PipelineOptions& options, Progress* progress) {
  const ImageUndistorter undistorter(sequence.calibration.camera);
  const int n = static_cast<int>(images.size());
  std::vector<FrameFeatures> features(n);
  for (int i = 0; i < n; ++i) {
    progress->Update("junction detection", "frame", i + 1, n);
    features[i].segments = DetectLineSegments(undistorter.Apply(images[i]), options.segments);
    features[i].junctions = DetectJunctions(features[i].segments, options.junctions);
    features[i].graph = BuildTopologyGraph(features[i].junctions);
  }
  progress->Finish();
  return features;
}

// Paper sections 3-4 on every consecutive pair, F from the calibration and the odometry.
std::vector<PairMatches> MatchConsecutiveFrames(const Sequence& sequence,
                                                const std::vector<FrameFeatures>& features,
                                                const PipelineOptions& options, Progress* progress) {
  const Calibration& calibration = sequence.calibration;
  const int n = static_cast<int>(features.size());
  std::vector<PairMatches> pairs;
  for (int i = 0; i + 1 < n; ++i) {
    progress->Update("matching", "pair", i + 1, n - 1);
    const Eigen::Matrix3d F =
        FundamentalFromOdometry(calibration.camera.K(), calibration.base_T_camera,
                                sequence.frames[i].world_T_base_odometry, sequence.frames[i + 1].world_T_base_odometry);
    PairMatches pair;
    pair.frame_a = i;
    pair.frame_b = i + 1;
    pair.matches = MatchJunctions(features[i].junctions, features[i].graph, features[i + 1].junctions,
                                  features[i + 1].graph, F, options.matching);
    pairs.push_back(std::move(pair));
  }
  progress->Finish();
  return pairs;
}

std::vector<StampedPose> CameraTrajectory(const Sequence& sequence, bool groundtruth) {
  std::vector<StampedPose> trajectory;
  trajectory.reserve(sequence.frames.size());
  for (const Frame& frame : sequence.frames) {
    const Pose3& world_T_base = groundtruth ? *frame.world_T_base_groundtruth : frame.world_T_base_odometry;
    trajectory.push_back({frame.timestamp, world_T_base * sequence.calibration.base_T_camera});
  }
  return trajectory;
}

std::string FrameFileStem(int frame) {
  char stem[16];
  std::snprintf(stem, sizeof(stem), "%06d", frame);
  return stem;
}

std::string MatchesCsv(const PairMatches& pair, const std::vector<FrameFeatures>& features) {
  const Junctions& a = features[pair.frame_a].junctions;
  const Junctions& b = features[pair.frame_b].junctions;
  std::string csv = "id_a,id_b,similarity\n";
  for (const JunctionMatch& match : pair.matches) {
    csv += std::to_string(a[match.index_a].id) + "," + std::to_string(b[match.index_b].id) + "," +
           JsonNumber(match.similarity) + "\n";
  }
  return csv;
}

template <typename T, typename Count>
std::string JsonCountList(const std::vector<T>& items, Count count) {
  std::string list = "[";
  for (size_t i = 0; i < items.size(); ++i) list += (i ? ", " : "") + std::to_string(count(items[i]));
  return list + "]";
}

std::string MetricsJson(const Sequence& sequence, const RunResult& result) {
  const StageTimes& times = result.times;
  std::ostringstream json;
  json << "{\n"
       << "  \"frames\": " << sequence.frames.size() << ",\n"
       << "  \"junctions_per_frame\": "
       << JsonCountList(result.features, [](const FrameFeatures& f) { return f.junctions.size(); }) << ",\n"
       << "  \"matches_per_pair\": "
       << JsonCountList(result.pairs, [](const PairMatches& p) { return p.matches.size(); }) << ",\n"
       << "  \"tracks\": null,\n"
       << "  \"points3d\": null,\n"
       << "  \"lines3d\": null,\n"
       << "  \"ate_odometry_m\": null,\n"
       << "  \"ate_refined_m\": null,\n"
       << "  \"rpe_odometry\": null,\n"
       << "  \"rpe_refined\": null,\n"
       << "  \"time_s\": {\"frontend\": " << JsonNumber(times.frontend)
       << ", \"matching\": " << JsonNumber(times.matching) << ", \"backend\": " << JsonNumber(times.backend)
       << ", \"total\": " << JsonNumber(times.total) << "}\n"
       << "}\n";
  return json.str();
}

Status WriteOutputs(const Sequence& sequence, const PipelineOptions& options, const RunResult& result) {
  const fs::path out(options.output_dir);
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((out / "junctions").string()));
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((out / "matches").string()));
  const Camera& camera = sequence.calibration.camera;
  for (size_t i = 0; i < result.features.size(); ++i) {
    const std::string json = JunctionsToJson(static_cast<int>(i), sequence.frames[i].image_path, camera.width,
                                             camera.height, result.features[i].junctions);
    SFM_RETURN_IF_ERROR(WriteFileAtomically((out / "junctions" / (FrameFileStem(i) + ".json")).string(), json));
  }
  for (const PairMatches& pair : result.pairs) {
    const std::string name = FrameFileStem(pair.frame_a) + "_" + FrameFileStem(pair.frame_b) + ".csv";
    SFM_RETURN_IF_ERROR(WriteFileAtomically((out / "matches" / name).string(), MatchesCsv(pair, result.features)));
  }
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((out / "trajectory_odometry.txt").string(),
                                         CameraTrajectory(sequence, /*groundtruth=*/false)));
  if (sequence.has_groundtruth) {
    SFM_RETURN_IF_ERROR(WriteTumTrajectory((out / "trajectory_groundtruth.txt").string(),
                                           CameraTrajectory(sequence, /*groundtruth=*/true)));
  }
  return WriteFileAtomically((out / "metrics.json").string(), MetricsJson(sequence, result));
}

}  // namespace

Status PipelineOptions::Check() const {
  if (output_dir.empty()) return Status::Error("--output must name a directory");
  SFM_RETURN_IF_ERROR(segments.Check());
  SFM_RETURN_IF_ERROR(junctions.Check());
  return matching.Check();
}

Status RunPipeline(const PipelineOptions& options) {
  const Clock::time_point start = Clock::now();
  SFM_RETURN_IF_ERROR(options.Check());

  // 1. Read and validate all input before anything is written.
  Sequence sequence;
  SFM_RETURN_IF_ERROR(ReadSequence(options.sequence_dir, &sequence));
  LOG(INFO) << "sequence " << options.sequence_dir << ": " << sequence.frames.size() << " frames, "
            << sequence.calibration.camera.width << "x" << sequence.calibration.camera.height
            << (sequence.has_groundtruth ? ", with ground truth" : ", no ground truth");
  Progress progress(options.show_progress);
  std::vector<cv::Mat> images;
  SFM_RETURN_IF_ERROR(LoadImages(sequence, &progress, &images));
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(options.output_dir));

  // 2. Front end and matching.
  RunResult result;
  Clock::time_point stage_start = Clock::now();
  result.features = DetectFeatures(sequence, images, options, &progress);
  result.times.frontend = SecondsSince(stage_start);
  stage_start = Clock::now();
  result.pairs = MatchConsecutiveFrames(sequence, result.features, options, &progress);
  result.times.matching = SecondsSince(stage_start);
  // Stages of a later issue say plainly that they did not run; no output is faked for them.
  LOG(WARNING) << "tracks, triangulation and bundle adjustment are not implemented yet; not written: "
                  "tracks.csv, trajectory_refined.txt, wireframe.ply, colmap/";

  // 3. Outputs.
  result.times.total = SecondsSince(start);
  SFM_RETURN_IF_ERROR(WriteOutputs(sequence, options, result));
  LOG(INFO) << "time: frontend " << result.times.frontend << " s, matching " << result.times.matching
            << " s, backend " << result.times.backend << " s, total " << result.times.total << " s";
  return Status::Ok();
}

}  // namespace sfm

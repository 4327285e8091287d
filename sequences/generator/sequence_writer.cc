#include "sequences/generator/sequence_writer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <glog/logging.h>
#include <opencv2/imgcodecs.hpp>

#include "geometry/tum_io.h"
#include "frontend/sequence/sequence.h"
#include "util/atomic_file.h"
#include "sequences/generator/ground_truth.h"
#include "sequences/generator/random.h"
#include "sequences/generator/wireframe.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

// Sub-streams of the master seed.
constexpr std::uint64_t kSceneStream = 1, kOdometryStream = 2, kFrameNoiseStream = 1000;

// The parts of a sequence directory GenerateSequence writes.
const char* const kOutputs[] = {"sequence.yaml", "images.txt", "odometry.txt", "groundtruth.txt", "images", "truth"};

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

Status PrepareDirectory(const std::string& directory, bool overwrite) {
  std::error_code error;
  for (const char* name : kOutputs) {
    const fs::path path = fs::path(directory) / name;
    if (!fs::exists(path, error)) continue;
    if (!overwrite) {
      return Status::Error(directory + ": holds a sequence already (" + name +
                           "); choose another directory, or overwrite it (make_sequence --overwrite)");
    }
    fs::remove_all(path, error);
    if (error) return Status::Error(path.string() + ": cannot remove (" + error.message() + ")");
  }
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((fs::path(directory) / "images").string()));
  return Status::Ok();
}

std::uintmax_t DirectorySize(const fs::path& root) {
  std::uintmax_t total = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) total += entry.file_size();
  }
  return total;
}

}  // namespace

Status GeneratorOptions::Check() const {
  SFM_RETURN_IF_ERROR(scene.Check());
  SFM_RETURN_IF_ERROR(trajectory.Check());
  SFM_RETURN_IF_ERROR(camera.Check());
  SFM_RETURN_IF_ERROR(render.Check());
  SFM_RETURN_IF_ERROR(odometry.Check());
  if (!(frame_rate > 0 && frame_rate <= 1000)) return Status::Error("frame_rate must be in (0, 1000] Hz");
  if (png_compression < 0 || png_compression > 9) return Status::Error("png_compression must be in [0, 9]");
  if (!(visibility.sample_spacing > 0 && visibility.min_segment_length >= 0 && visibility.depth_tolerance >= 0)) {
    return Status::Error("visibility: need sample_spacing > 0, min_segment_length >= 0, depth_tolerance >= 0");
  }
  if (scene.type == SceneType::kCorridor && scene.corridor_length == 0 && trajectory.num_frames == 0) {
    return Status::Error("a corridor fitted to the trajectory (corridor_length 0) needs num_frames > 0");
  }
  return Status::Ok();
}

Status GenerateSequence(const GeneratorOptions& options, const std::string& directory, bool overwrite,
                        GenerationReport* report) {
  const auto start = std::chrono::steady_clock::now();
  SFM_RETURN_IF_ERROR(options.Check());
  GenerationReport local_report;
  GenerationReport& r = report != nullptr ? *report : local_report;
  r = GenerationReport();

  // Scene, fitted to the trajectory when asked.
  SceneOptions scene_options = options.scene;
  if (scene_options.type == SceneType::kCorridor && scene_options.corridor_length == 0) {
    scene_options.corridor_length =
        options.trajectory.start_margin + TrajectoryExtentX(options.trajectory) + options.trajectory.end_margin;
  }
  Scene scene;
  SFM_RETURN_IF_ERROR(BuildScene(scene_options, MixSeed(options.seed, kSceneStream), &scene));
  r.corridor_length = scene_options.type == SceneType::kCorridor ? scene_options.corridor_length : 0;
  std::vector<Pose3> world_T_base;
  SFM_RETURN_IF_ERROR(MakeTrajectory(options.trajectory, scene, &world_T_base));
  const std::vector<Pose3> odometry =
      SimulateOdometry(world_T_base, options.odometry, MixSeed(options.seed, kOdometryStream));

  Calibration calibration;
  calibration.camera = options.camera.MakeCamera();
  calibration.base_T_camera = options.camera.BaseTCamera();
  calibration.odometry_noise = options.odometry.ForCalibration();
  calibration.odometry_noise_given = true;

  GroundTruth truth;
  truth.wireframe = ExtractWireframe(scene);
  r.faces = static_cast<int>(scene.faces.size());
  r.wireframe_vertices = static_cast<int>(truth.wireframe.vertices.size());
  r.wireframe_edges = static_cast<int>(truth.wireframe.edges.size());

  SFM_RETURN_IF_ERROR(PrepareDirectory(directory, overwrite));
  const fs::path root(directory);
  const Renderer renderer(scene, calibration.camera, options.render);
  VisibilityOptions visibility = options.visibility;
  visibility.near = options.render.near;
  std::vector<StampedPose> groundtruth_poses, odometry_poses;
  std::string image_list = "# timestamp image (junction-sfm synthetic sequence, docs/generator.md)\n";
  Canvas canvas;
  // Huffman-only coding: the images are flat regions plus sensor noise, which LZ77 matching cannot
  // shorten; it gives files ~12% smaller than zlib's default strategy, and faster.
  const std::vector<int> png_parameters = {cv::IMWRITE_PNG_COMPRESSION, options.png_compression,
                                           cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY};
  const std::uint64_t noise_seed = options.image_noise_seed != 0 ? options.image_noise_seed : options.seed;
  for (size_t i = 0; i < world_T_base.size(); ++i) {
    const int index = static_cast<int>(i);
    const double timestamp = index / options.frame_rate;
    const Pose3 world_T_camera = world_T_base[i] * calibration.base_T_camera;
    auto render_start = std::chrono::steady_clock::now();
    const cv::Mat image =
        renderer.Render(world_T_camera, MixSeed(noise_seed, kFrameNoiseStream + i), &canvas);
    r.render_seconds += Seconds(render_start);
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06d.png", index);
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image, png, png_parameters)) {
      return Status::Error((root / name).string() + ": PNG encoding failed");
    }
    SFM_RETURN_IF_ERROR(WriteFileAtomically((root / name).string(), std::string(png.begin(), png.end())));
    char line[64];
    std::snprintf(line, sizeof(line), "%.6f %s\n", timestamp, name);
    image_list += line;
    groundtruth_poses.push_back({timestamp, world_T_base[i]});
    odometry_poses.push_back({timestamp, odometry[i]});
    if (options.write_truth) {
      const auto truth_start = std::chrono::steady_clock::now();
      FrameTruth frame;
      frame.index = index;
      frame.timestamp = timestamp;
      ComputeFrameTruth(scene, truth.wireframe, calibration.camera, world_T_camera, canvas, visibility, &frame);
      truth.frames.push_back(std::move(frame));
      r.truth_seconds += Seconds(truth_start);
    }
  }
  r.frames = static_cast<int>(world_T_base.size());
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "images.txt").string(), image_list));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "odometry.txt").string(), odometry_poses));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "groundtruth.txt").string(), groundtruth_poses));
  if (options.write_truth) SFM_RETURN_IF_ERROR(WriteGroundTruth(directory, scene, truth));
  // Last, so that a directory with sequence.yaml is a complete sequence.
  SFM_RETURN_IF_ERROR(WriteCalibration((root / "sequence.yaml").string(), calibration));
  r.bytes = DirectorySize(root);
  r.total_seconds = Seconds(start);
  return Status::Ok();
}

}  // namespace sfm

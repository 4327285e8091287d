// make_sequence: renders a synthetic indoor sequence with ground truth (docs/generator.md).
//
//   build/bin/make_sequence --output <sequence dir> [--scene=corridor|room]
//                           [--trajectory=straight|loop|turns] [--frames=N] [--seed=S] [flags]
//
// Writes a SPEC section 1 sequence (sequence.yaml, images.txt, images/, odometry.txt,
// groundtruth.txt) plus truth/. With no other flag it makes the default sequence
// (sequences/regenerate_default.sh). Every default below is the library's (GeneratorOptions).
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>

#include "sequences/generator/sequence_writer.h"

namespace {
const sfm::GeneratorOptions kDefaults;
}  // namespace

// Output.
DEFINE_string(output, "", "Sequence directory to write (required); created if missing.");
DEFINE_bool(overwrite, false,
            "Replace a sequence already in --output (its sequence.yaml, images.txt, odometry.txt, "
            "groundtruth.txt, images/ and truth/; other files are kept).");
DEFINE_uint64(seed, kDefaults.seed, "Master seed: scene, odometry noise and image noise all derive from it.");
DEFINE_uint64(image_noise_seed, kDefaults.image_noise_seed,
              "If not 0, the image noise alone draws from this seed: the same sequence under a fresh "
              "noise draw (0: from --seed).");
DEFINE_int32(png_compression, kDefaults.png_compression, "PNG zlib level 0..9 (file size only; pixels are the same).");
DEFINE_bool(truth, kDefaults.write_truth, "Write the ground truth directory truth/.");
// Scene.
DEFINE_string(scene, sfm::SceneTypeName(kDefaults.scene.type), "Scene: corridor | room.");
DEFINE_double(corridor_length, kDefaults.scene.corridor_length,
              "Corridor length in m; 0: fitted to the trajectory (start margin + path + end margin).");
DEFINE_double(corridor_width, kDefaults.scene.corridor_width, "Corridor width in m.");
DEFINE_double(room_length, kDefaults.scene.room_length, "Room size along x in m.");
DEFINE_double(room_width, kDefaults.scene.room_width, "Room size along y in m.");
DEFINE_double(ceiling_height, kDefaults.scene.ceiling_height, "Floor to ceiling in m.");
DEFINE_bool(island, kDefaults.scene.island, "Room: a table and a box stack in the middle.");
DEFINE_bool(ceiling_lights, kDefaults.scene.ceiling_lights, "Bright panels on the ceiling.");
DEFINE_bool(sparse, kDefaults.scene.sparse,
            "Sparse scene: along the walls only cabinets and doors, 2-4 m apart; no posters, no island.");
// Trajectory.
DEFINE_string(trajectory, sfm::TrajectoryTypeName(kDefaults.trajectory.type),
              "Trajectory: straight (along the lane) | loop (round the room) | turns (weaving along the lane).");
DEFINE_int32(frames, kDefaults.trajectory.num_frames,
             "Number of frames; 0: the whole path (loop: one lap; straight/turns: to the end of the floor, "
             "needs --corridor_length in a corridor).");
DEFINE_double(step, kDefaults.trajectory.step, "Distance between frames on straight stretches, m.");
DEFINE_double(max_turn_per_frame, kDefaults.trajectory.max_turn_per_frame,
              "Largest heading change between two frames, rad (frames come closer on bends).");
DEFINE_double(lane_offset, kDefaults.trajectory.lane_offset, "Lateral offset of straight/turns from the lane, m (left > 0).");
DEFINE_double(frame_rate, kDefaults.frame_rate, "Frames per second (timestamps are index / frame_rate).");
// Camera.
DEFINE_int32(width, kDefaults.camera.width, "Image width, px.");
DEFINE_int32(height, kDefaults.camera.height, "Image height, px.");
DEFINE_double(fx, kDefaults.camera.fx, "Focal length x, px.");
DEFINE_double(fy, kDefaults.camera.fy, "Focal length y, px.");
DEFINE_double(cx, kDefaults.camera.cx, "Principal point x, px; negative: (width - 1) / 2.");
DEFINE_double(cy, kDefaults.camera.cy, "Principal point y, px; negative: (height - 1) / 2.");
DEFINE_string(lens, sfm::DistortionModelName(kDefaults.camera.model),
              "Lens model (sequence.yaml's distortion_model): radtan (OpenCV's k1 k2 p1 p2 k3; all zero: a "
              "pinhole) | equidistant (cv::fisheye's k1 k2 k3 k4; --fx, --fy default to a 150 degree "
              "diagonal field of view).");
DEFINE_double(k1, kDefaults.camera.distortion[0], "Radial distortion k1 (radtan or equidistant).");
DEFINE_double(k2, kDefaults.camera.distortion[1], "Radial distortion k2 (radtan or equidistant).");
DEFINE_double(p1, kDefaults.camera.distortion[2], "Tangential distortion p1 (radtan).");
DEFINE_double(p2, kDefaults.camera.distortion[3], "Tangential distortion p2 (radtan).");
DEFINE_double(k3, kDefaults.camera.distortion[4], "Radial distortion k3 (radtan or equidistant).");
DEFINE_double(k4, 0, "Radial distortion k4 (equidistant).");
DEFINE_double(camera_height, kDefaults.camera.mount_height, "Camera centre above the floor, m.");
DEFINE_double(camera_forward, kDefaults.camera.mount_forward, "Camera centre ahead of the robot base origin, m.");
DEFINE_double(camera_pitch, kDefaults.camera.pitch, "Optical axis below the horizontal, rad.");
// Rendering.
DEFINE_int32(supersampling, kDefaults.render.supersampling, "Anti-aliasing samples per pixel along each axis, 1..8.");
DEFINE_double(blur_sigma, kDefaults.render.blur_sigma, "Gaussian blur sigma, px (0: none).");
DEFINE_double(noise_sigma, kDefaults.render.noise_sigma, "Additive Gaussian image noise sigma, grey levels (0: none).");
// Odometry noise.
DEFINE_double(odometry_scale_error, kDefaults.odometry.scale_error,
              "Odometry distance scale error: it reports (1 + this) x the true distance.");
DEFINE_double(odometry_distance_sigma, kDefaults.odometry.distance_sigma,
              "Odometry distance noise per frame, fraction of the step (Gaussian sigma).");
DEFINE_double(odometry_heading_sigma, kDefaults.odometry.heading_sigma,
              "Odometry heading noise per frame, rad (Gaussian sigma).");
DEFINE_double(odometry_heading_bias, kDefaults.odometry.heading_bias,
              "Odometry heading bias per frame, rad (positive: drifts left).");
DEFINE_double(odometry_noise_scale, 1.0,
              "Multiplies the four odometry noise terms above, defaults or given (3: three times as poor).");

namespace {

// --lens=equidistant's field of view across the image diagonal when --fx, --fy are not given: a
// typical robot fisheye (issue 21).
constexpr double kEquidistantDiagonalDeg = 150;

// Builds the options from the flags; false with a message when a name is not known.
bool OptionsFromFlags(sfm::GeneratorOptions* options, std::string* problem) {
  if (!sfm::ParseSceneType(FLAGS_scene, &options->scene.type)) {
    *problem = "--scene must be corridor or room, not '" + FLAGS_scene + "'";
    return false;
  }
  if (!sfm::ParseTrajectoryType(FLAGS_trajectory, &options->trajectory.type)) {
    *problem = "--trajectory must be straight, loop or turns, not '" + FLAGS_trajectory + "'";
    return false;
  }
  options->seed = FLAGS_seed;
  options->image_noise_seed = FLAGS_image_noise_seed;
  options->png_compression = FLAGS_png_compression;
  options->write_truth = FLAGS_truth;
  options->frame_rate = FLAGS_frame_rate;
  options->scene.corridor_length = FLAGS_corridor_length;
  options->scene.corridor_width = FLAGS_corridor_width;
  options->scene.room_length = FLAGS_room_length;
  options->scene.room_width = FLAGS_room_width;
  options->scene.ceiling_height = FLAGS_ceiling_height;
  options->scene.island = FLAGS_island;
  options->scene.ceiling_lights = FLAGS_ceiling_lights;
  options->scene.sparse = FLAGS_sparse;
  options->trajectory.num_frames = FLAGS_frames;
  options->trajectory.step = FLAGS_step;
  options->trajectory.max_turn_per_frame = FLAGS_max_turn_per_frame;
  options->trajectory.lane_offset = FLAGS_lane_offset;
  options->camera.width = FLAGS_width;
  options->camera.height = FLAGS_height;
  options->camera.fx = FLAGS_fx;
  options->camera.fy = FLAGS_fy;
  options->camera.cx = FLAGS_cx;
  options->camera.cy = FLAGS_cy;
  if (!sfm::ParseDistortionModel(FLAGS_lens, &options->camera.model)) {
    *problem = "--lens must be radtan or equidistant, not '" + FLAGS_lens + "'";
    return false;
  }
  if (options->camera.model == sfm::DistortionModel::kEquidistant) {
    if (FLAGS_p1 != 0 || FLAGS_p2 != 0) {
      *problem = "--lens=equidistant has no tangential terms: leave --p1 and --p2 at 0";
      return false;
    }
    options->camera.distortion = {FLAGS_k1, FLAGS_k2, FLAGS_k3, FLAGS_k4, 0};
    const double focal = options->camera.EquidistantFocalForDiagonal(kEquidistantDiagonalDeg * M_PI / 180);
    if (gflags::GetCommandLineFlagInfoOrDie("fx").is_default) options->camera.fx = focal;
    if (gflags::GetCommandLineFlagInfoOrDie("fy").is_default) options->camera.fy = focal;
  } else {
    if (FLAGS_k4 != 0) {
      *problem = "--k4 is a coefficient of --lens=equidistant only";
      return false;
    }
    options->camera.distortion = {FLAGS_k1, FLAGS_k2, FLAGS_p1, FLAGS_p2, FLAGS_k3};
  }
  options->camera.mount_height = FLAGS_camera_height;
  options->camera.mount_forward = FLAGS_camera_forward;
  options->camera.pitch = FLAGS_camera_pitch;
  options->render.supersampling = FLAGS_supersampling;
  options->render.blur_sigma = FLAGS_blur_sigma;
  options->render.noise_sigma = FLAGS_noise_sigma;
  options->odometry.scale_error = FLAGS_odometry_scale_error;
  options->odometry.distance_sigma = FLAGS_odometry_distance_sigma;
  options->odometry.heading_sigma = FLAGS_odometry_heading_sigma;
  options->odometry.heading_bias = FLAGS_odometry_heading_bias;
  if (!(FLAGS_odometry_noise_scale >= 0)) {
    *problem = "--odometry_noise_scale must be >= 0, not " + std::to_string(FLAGS_odometry_noise_scale);
    return false;
  }
  options->odometry = options->odometry.Scaled(FLAGS_odometry_noise_scale);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  gflags::SetUsageMessage(
      "renders a synthetic indoor sequence with ground truth (docs/generator.md).\n"
      "  make_sequence --output <sequence dir> [--scene=corridor|room] [--trajectory=straight|loop|turns] "
      "[--frames=N] [--seed=S]");
  gflags::ParseCommandLineFlags(&argc, &argv, true);
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);

  if (argc > 1) {
    std::fprintf(stderr, "make_sequence: unexpected argument '%s' (flags are --name=value; see --help)\n", argv[1]);
    return 2;
  }
  if (FLAGS_output.empty()) {
    std::fprintf(stderr, "make_sequence: --output is required: the sequence directory to write\n");
    return 2;
  }
  sfm::GeneratorOptions options;
  std::string problem;
  if (!OptionsFromFlags(&options, &problem)) {
    std::fprintf(stderr, "make_sequence: %s\n", problem.c_str());
    return 2;
  }
  const sfm::Status valid = options.Check();
  if (!valid.ok()) {
    std::fprintf(stderr, "make_sequence: %s\n", valid.message().c_str());
    return 2;
  }
  sfm::GenerationReport report;
  const sfm::Status status = sfm::GenerateSequence(options, FLAGS_output, FLAGS_overwrite, &report);
  if (!status.ok()) {
    std::fprintf(stderr, "make_sequence: %s\n", status.message().c_str());
    return 1;
  }
  std::printf("make_sequence: %d frames in %s (%.1f MB): %s scene of %d faces, wireframe of %d vertices and %d edges\n",
              report.frames, FLAGS_output.c_str(), report.bytes / 1e6, FLAGS_scene.c_str(), report.faces,
              report.wireframe_vertices, report.wireframe_edges);
  std::printf("make_sequence: render %.1f ms/frame, ground truth %.1f ms/frame, total %.2f s\n",
              1e3 * report.render_seconds / report.frames, 1e3 * report.truth_seconds / report.frames,
              report.total_seconds);
  return 0;
}

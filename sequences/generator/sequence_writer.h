// Generates a whole synthetic sequence: scene, trajectory, images, odometry and ground truth, and
// writes it as a SPEC section 1 sequence directory plus truth/ (see ground_truth.h).
//
//   <dir>/sequence.yaml      calibration (WriteCalibration), with the odometry noise model
//   <dir>/images.txt         "<timestamp> images/NNNNNN.png", timestamps i / frame_rate
//   <dir>/images/NNNNNN.png  8-bit grey
//   <dir>/odometry.txt       noisy world_T_base (TUM), starting on the true first pose
//   <dir>/groundtruth.txt    true world_T_base (TUM)
//   <dir>/truth/...          wireframe, scene and per-frame visibility
// The same options give the same bytes: every random number comes from `seed` through MixSeed.
#pragma once

#include <cstdint>
#include <string>

#include "util/status.h"
#include "sequences/generator/camera_rig.h"
#include "sequences/generator/odometry_noise.h"
#include "sequences/generator/renderer.h"
#include "sequences/generator/scene_builder.h"
#include "sequences/generator/trajectory.h"
#include "sequences/generator/visibility.h"

namespace sfm {

struct GeneratorOptions {
  SceneOptions scene;  // a corridor_length of 0 is fitted to the trajectory
  TrajectoryOptions trajectory;
  CameraRigOptions camera;
  RenderOptions render;
  OdometryNoiseOptions odometry;
  VisibilityOptions visibility;  // its `near` is taken from render.near
  std::uint64_t seed = 1;
  // The frames' sensor noise alone draws from this seed when it is not 0 (0: from `seed`, as every
  // other random number). Another value gives the same scene, trajectory, odometry and noise-free
  // pixels under a fresh noise draw: how an end-to-end comparison tells an effect from the noise of
  // one draw (docs/decisions.md).
  std::uint64_t image_noise_seed = 0;
  double frame_rate = 10;   // Hz
  int png_compression = 9;  // zlib level 0..9 (smaller files, same pixels)
  bool write_truth = true;  // truth/ directory

  GeneratorOptions() { scene.corridor_length = 0; }
  Status Check() const;
};

// What GenerateSequence did, for reports and tests.
struct GenerationReport {
  int frames = 0;
  int faces = 0;                   // scene polygons
  int wireframe_vertices = 0;
  int wireframe_edges = 0;
  double corridor_length = 0;      // m, as built (corridor scenes)
  double render_seconds = 0;       // rasterising and shading all frames
  double truth_seconds = 0;        // per-frame visibility
  double total_seconds = 0;
  std::uintmax_t bytes = 0;        // size of everything written
};

// Writes the sequence into `directory`, creating it if needed. Fails when `directory` holds a
// sequence already (sequence.yaml, images.txt, images/ or truth/) unless `overwrite`, which first
// removes exactly those (and odometry.txt, groundtruth.txt), leaving other files alone.
Status GenerateSequence(const GeneratorOptions& options, const std::string& directory, bool overwrite,
                        GenerationReport* report = nullptr);

}  // namespace sfm

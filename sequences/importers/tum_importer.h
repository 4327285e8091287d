// TUM RGB-D benchmark folders (Sturm et al., IROS 2012; vision.in.tum.de/data/datasets/rgbd-dataset):
// rgb.txt ("timestamp rgb/<file>.png" lines), rgb/*.png, and groundtruth.txt (TUM trajectory of
// the colour camera's optical centre, world_T_camera with the camera's z forward, from motion capture).
#pragma once

#include <string>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"
#include "sequences/importers/imported_sequence.h"

namespace sfm {

// The three Kinects of the benchmark ("Freiburg 1/2/3"), whose colour cameras have published
// calibrations (fr3's with zero distortion).
enum class TumCamera { kFreiburg1, kFreiburg2, kFreiburg3 };

// "fr1", "fr2" or "fr3".
Status ParseTumCamera(const std::string& name, TumCamera* camera);

// The published K and distortion (k1 k2 p1 p2 k3) of the colour camera, for 640x480 images.
Camera TumCameraModel(TumCamera camera);

struct TumImportOptions {
  TumCamera camera = TumCamera::kFreiburg1;
  int stride = 1;                     // keep every stride-th image that has ground truth (30 Hz is dense)
  double max_groundtruth_gap = 0.05;  // s: images between two ground-truth poses further apart are skipped

  Status Check() const;
};

// Reads the folder. Each image's true pose is interpolated between the ground-truth poses just
// before and after its timestamp; images outside the ground truth's time span or in a gap longer
// than max_groundtruth_gap are skipped (and counted in the log). Fails, naming the file (and line),
// on a missing folder or file, a malformed rgb.txt line, timestamps that do not increase, a bad
// groundtruth.txt (ReadTumTrajectory), or fewer than 2 images left.
Status ReadTumSequence(const std::string& input_dir, const TumImportOptions& options, ImportedSequence* sequence);

}  // namespace sfm

// A data set read into memory (camera, image files, true camera poses) and written as a SPEC
// sequence directory (SPEC section 1) with simulated odometry.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"
#include "sequences/importers/camera_odometry_noise.h"
#include "sequences/importers/image_scaling.h"

namespace sfm {

// Seconds between frames given to data sets without timestamps (SPEC needs a time per frame).
constexpr double kFrameInterval = 0.1;

struct ImportedFrame {
  double timestamp = 0;      // seconds
  std::string source_image;  // path of the data set's image file
  Pose3 world_T_camera;      // ground truth
  // When set, the source image is resampled (bicubic) by this affine map, sequence pixel =
  // A (source pixel; 1) in OpenCV's pixel-centre convention, into the camera's width x height
  // (e.g. to a shared K: shared_intrinsics_warp.h). The source must then be source_width x source_height.
  std::optional<Eigen::Matrix<double, 2, 3>> source_to_image;
};

struct ImportedSequence {
  Camera camera;  // of the source images (after their warps, when frames have one), before any scaling
  // Of the data set's images when frames are warped (0: the camera's size).
  int source_width = 0, source_height = 0;
  std::vector<ImportedFrame> frames;
  // Lines for the sequence's import_notes.txt: where K, the poses and the world frame come from.
  std::vector<std::string> notes;
};

struct SequenceWriteOptions {
  ImageScaleOptions scale;
  CameraOdometryNoiseOptions odometry;
  std::uint64_t seed = 1;  // of the odometry noise
  bool overwrite = false;  // replace an existing non-empty output directory

  Status Check() const;
};

// Writes `output_dir`: sequence.yaml (scaled camera, T_base_camera identity since the poses are
// camera poses, the odometry noise model), images/NNNNNN.png, images.txt, groundtruth.txt (the true
// poses), odometry.txt (SimulateCameraOdometry), import_notes.txt (the sequence's notes and the
// options used), and image_warps.txt when frames are warped (each frame's source_to_image composed
// with the scaling: what maps the data set's own image measurements to the sequence's pixels).
// Everything goes to a temporary sibling directory first, renamed into place at the
// end, so a failed import leaves no output. Fails, naming the file, on an image that does not
// decode or is not of the camera's size, an existing non-empty output without overwrite, or a
// write error.
Status WriteImportedSequence(const ImportedSequence& sequence, const SequenceWriteOptions& options,
                             const std::string& output_dir);

// Reads image_warps.txt as WriteImportedSequence writes it: per image in order, the affine map
// (2 x 3) from the data set's pixels to the sequence's. For consumers that compare the sequence
// with the data set's own image measurements (docs/importers.md). Fails, naming the file and the
// line, on a missing file, a malformed row or a non-finite entry.
Status ReadImageWarps(const std::string& path, std::vector<Eigen::Matrix<double, 2, 3>>* warps);

}  // namespace sfm

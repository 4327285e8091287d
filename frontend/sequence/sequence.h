// A sequence directory (SPEC section 1): calibration, image list, odometry, optional ground truth,
// read and validated in one place so that every later stage can trust it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

// Odometry noise model used to weight the odometry (sequence.yaml, optional keys).
struct OdometryNoise {
  double translation_sigma = 0.05;  // fraction of the distance travelled between two frames
  double rotation_sigma = 0.01;     // radians per frame
};

struct Calibration {
  Camera camera;
  Pose3 base_T_camera;
  OdometryNoise odometry_noise;
  bool odometry_noise_given = false;  // both keys present in sequence.yaml
};

struct Frame {
  int index = 0;                       // 0-based index into images.txt
  double timestamp = 0;                // seconds
  std::string image_path;              // as written in images.txt (relative to the sequence)
  Pose3 world_T_base_odometry;         // from odometry.txt, associated by timestamp
  std::optional<Pose3> world_T_base_groundtruth;  // from groundtruth.txt, when present

  Pose3 WorldTCameraOdometry(const Calibration& c) const { return world_T_base_odometry * c.base_T_camera; }
};

struct Sequence {
  std::string directory;
  Calibration calibration;
  std::vector<Frame> frames;
  bool has_groundtruth = false;  // every frame then has world_T_base_groundtruth
};

// A trajectory line is an image's pose when their timestamps differ by at most this (SPEC: 1 ms);
// it is also how far an image may lie outside a trajectory's time span.
constexpr double kTimestampTolerance = 1e-3;

// Reads sequence.yaml. Fails, naming the file and the key, on a missing file, a missing key, a
// key of the wrong shape or type, a non-finite value, non-positive sizes or focal lengths, and a
// T_base_camera whose rotation part is not a rotation. A file without OpenCV's "%YAML:1.0" first
// line is accepted (OpenCV 4.6 alone would reject it).
Status ReadCalibration(const std::string& yaml_path, Calibration* calibration);

// Writes sequence.yaml in the SPEC layout (cv::FileStorage YAML), atomically. The odometry noise
// keys are written only when odometry_noise_given, so that reading the file back gives the same.
Status WriteCalibration(const std::string& yaml_path, const Calibration& calibration);

// Reads and validates a whole sequence directory: sequence.yaml, images.txt, odometry.txt and
// groundtruth.txt when present. Each image's pose (from each trajectory file) is the line whose
// timestamp is nearest, when within kTimestampTolerance, used as is; otherwise, for an image between
// two lines, the pose interpolated between them (translation linear, rotation slerp), said once per
// file in the log. An image further than kTimestampTolerance outside a file's time span is an error
// naming the image's line, its timestamp and the file (nothing is extrapolated). Image files are
// checked to exist but not decoded (LoadFrameImage does that).
Status ReadSequence(const std::string& directory, Sequence* sequence);

// Decodes the image of a frame as 8-bit grey. Fails, naming the file, when it does not exist,
// does not decode, or is not of the calibrated size.
Status LoadFrameImage(const Sequence& sequence, int frame_index, cv::Mat* grey);

}  // namespace sfm

// EuRoC / ASL folders (Burri et al., IJRR 2016; the ASL data set format): cam0/data.csv
// ("timestamp [ns],filename" lines), cam0/data/*.png, cam0/sensor.yaml (pinhole intrinsics, the
// distortion model, T_BS), and, where present, state_groundtruth_estimate0/data.csv (the body's
// true pose, ASL CSV). ASL folders hold no wheel odometry: the user names an odometry file (TUM, or
// the ASL CSV layout). Written as a SPEC sequence with the real odometry (nothing simulated).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frontend/sequence/sequence.h"
#include "geometry/pose.h"
#include "geometry/tum_io.h"
#include "util/status.h"

namespace sfm {

// A robot's recording: the calibration, and per image its time, file, odometry pose and (when
// known) true pose of the base.
struct RecordedFrame {
  double timestamp = 0;        // seconds
  std::string source_image;    // the image file, copied into the sequence byte for byte
  Pose3 world_T_base_odometry;
  std::optional<Pose3> world_T_base_groundtruth;
};

struct RecordedSequence {
  Calibration calibration;
  std::vector<RecordedFrame> frames;
  std::vector<std::string> notes;  // for import_notes.txt: where each part comes from
};

// Writes `output_dir` (SPEC section 1): sequence.yaml, images/NNNNNN.<ext> (the source files'
// bytes), images.txt, odometry.txt and, when every frame has one, groundtruth.txt (one line per
// frame, at the image's time), and import_notes.txt. Written to a temporary sibling and renamed into
// place, so a failed import leaves nothing. Fails, naming the file, on an image whose header does
// not declare the calibration's size, an existing non-empty output without `overwrite`, or a write
// error.
Status WriteRecordedSequence(const RecordedSequence& sequence, const std::string& output_dir, bool overwrite);

// A trajectory file: ASL CSV ("timestamp [ns],x,y,z,qw,qx,qy,qz[,...]", as EuRoC's ground truth)
// when its first data line holds a comma, else TUM (ReadTumTrajectory). Fails naming the file and
// line on a malformed line, timestamps that do not increase, a quaternion not of unit norm.
Status ReadTrajectoryFile(const std::string& path, std::vector<StampedPose>* poses);

// The pose at time t: the sample within 1 ms (SPEC section 1), else between the two samples around
// t (translation linear, rotation slerp). False outside the trajectory's span (beyond 1 ms).
bool TrajectoryPoseAt(const std::vector<StampedPose>& poses, double t, Pose3* pose);

struct EurocImportOptions {
  std::string odometry_path;     // required: TUM or ASL CSV, world_T_base
  std::string calibration_path;  // optional: replaces cam0/sensor.yaml (ReadCalibrationFile)
  // The body (EuRoC's B, the IMU) in the robot base frame: T_base_camera = base_T_body * T_BS, and
  // the ground truth's world_T_body becomes world_T_base = world_T_body * base_T_body^-1.
  Pose3 base_T_body;
};

// Reads the folder. Images outside the ground truth's span are left out (counted in the notes);
// the odometry must cover every image. Fails, naming the file (and line), on a missing folder or
// file, a malformed line, timestamps that do not increase, odometry that ends before the images or
// starts after them, a calibration ReadCalibrationFile refuses, or fewer than 2 images left.
Status ReadEurocSequence(const std::string& input_dir, const EurocImportOptions& options,
                         RecordedSequence* sequence);

}  // namespace sfm

// A robot's recording (recording.h: a ROS 2 or ROS 1 bag) as a SPEC sequence directory (SPEC
// section 1): the images of one image topic, the robot's own odometry interpolated at their stamps, the
// camera from a CameraInfo topic, T_base_camera from /tf_static, and ground truth from an optional pose
// topic.
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "frontend/sequence/sequence.h"
#include "sequences/importers/image_scaling.h"
#include "sequences/importers/rosbag/recording.h"
#include "util/status.h"

namespace sfm {

struct BagImportOptions {
  // Topics; empty: found automatically when the bag has exactly one topic of the kind (odometry:
  // nav_msgs/msg/Odometry, else geometry_msgs/msg/PoseStamped or TransformStamped). Ground truth
  // is read only when named.
  std::string image_topic, odometry_topic, camera_info_topic, groundtruth_topic;
  // Frame names for T_base_camera; empty: the odometry's child_frame_id and the images' frame_id.
  std::string base_frame, camera_frame;
  int every = 1;  // keep every N-th image (after the time window)
  double min_motion =
      0;  // m: then keep an image only when the odometry moved this far since the last kept one ...
  double min_rotation = 0;  // rad: ... or turned this much (0 and 0: keep all)
  double start_time = 0;    // s after the first image's stamp
  double end_time = std::numeric_limits<double>::infinity();  // s after the first image's stamp
  double max_odometry_gap = 0.5;  // s: images further than this from an odometry sample are not interpolated
  ImageScaleOptions scale;
  std::optional<OdometryNoise> odometry_noise;  // written to sequence.yaml when given
  // Given (import_sequence --calibration): the camera and T_base_camera, instead of the CameraInfo
  // topic and /tf_static.
  std::optional<Calibration> calibration;
  bool overwrite = false;

  Status Check() const;
};

// What an import did, for the log and the tests.
struct BagImportSummary {
  std::string image_topic, odometry_topic, camera_info_topic, groundtruth_topic;
  int images_on_topic = 0, frames = 0;
  int outside_window = 0, in_odometry_gaps = 0, dropped_by_every = 0, dropped_by_motion = 0;
  int mono16_shift = -1;  // bits a mono16 image was shifted right to 8 bits (-1: none was)
};

// Reads the recording and writes `output_dir` (images/NNNNNN.png, images.txt, odometry.txt,
// groundtruth.txt when a ground-truth topic is named, sequence.yaml, import_notes.txt) through a
// temporary sibling renamed into place, so a failed import leaves nothing. Fails with one line
// naming the bag, the topic and the problem: a named topic the bag does not have (the topics of
// the kind are listed), several candidates for an unnamed one (listed with types and counts), an
// empty topic, a topic that is not CDR of a ROS 2 schema or not of the expected type, a message
// that does not decode, images of changing size or of an unsupported encoding, odometry that
// starts after or stops before the images (by more than max_odometry_gap), ground truth that
// does not cover the kept images, a camera model other than plumb_bob or equidistant, no path
// from the base to the camera frame on /tf_static, fewer than 2 images kept, and the storage's
// errors (a corrupt MCAP file: truncated chunk, CRC mismatch, unknown compression).
Status ImportRecording(Recording* recording, const BagImportOptions& options, const std::string& output_dir,
                       BagImportSummary* summary);

// A ROS 2 bag (rosbag2_bag.h; a folder with metadata.yaml, or one .mcap or .db3 file), its
// messages decoded from CDR (ros2_messages.h), through ImportRecording.
Status ImportRosbag2(const std::string& bag_path, const BagImportOptions& options,
                     const std::string& output_dir, BagImportSummary* summary);

}  // namespace sfm

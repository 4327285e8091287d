// Camera poses of a COLMAP text model (images.txt) and their drift against a sequence's ground
// truth, measured as junction_sfm's metrics.json measures its own (docs/metrics.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"

namespace sfm {

// Reads COLMAP's images.txt (model_converter --output_type TXT): per image a line
// "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME" holding camera_T_world (COLMAP's projection is
// x = K (R X + t)), then one line of 2D points (possibly empty), skipped. Comment lines ('#') and
// blank lines before an image line are skipped, as COLMAP's own reader does. Returns
// world_T_camera keyed by NAME. Fails, naming the file and line, on a missing file, a malformed
// image line, a quaternion whose norm is not 1 within 1e-3, or a NAME given twice.
Status ReadColmapImagePoses(const std::string& images_txt,
                            std::map<std::string, Pose3>* world_T_camera_by_name);

// The drift of some frames' estimated poses against the sequence's ground truth (camera poses,
// world_T_base_groundtruth * base_T_camera), over those frames only.
struct FrameSubsetDrift {
  int frames = 0;               // in the sequence
  std::vector<int> registered;  // frame indices with an estimate, increasing
  double ate_m = 0;             // AbsoluteTrajectoryError over `registered`
  double ate_sim3_m = 0;        // AbsoluteTrajectoryErrorSim3 over `registered`
  double sim3_scale = 1;
};

// `world_T_camera_by_frame[i]` is frame i's estimate, or absent. Fails when the sequence has no
// ground truth.
Status ComputeFrameSubsetDrift(const Sequence& sequence, const std::map<int, Pose3>& world_T_camera_by_frame,
                               FrameSubsetDrift* drift);

}  // namespace sfm

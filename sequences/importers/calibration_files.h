// Camera calibrations as robots' tools write them, read into the sequence's Calibration (SPEC
// section 1): a Kalibr camchain YAML (cam0: pinhole with radtan or equidistant), a ROS camera_info
// YAML (the camera_calibration_parsers layout: plumb_bob or equidistant), an EuRoC / ASL
// sensor.yaml (camera_model pinhole, radial-tangential or equidistant, T_BS), or an OpenCV YAML as
// sequence.yaml itself (ReadCalibration). Parsed with yaml-cpp (Debian's libyaml-cpp-dev), except
// the OpenCV layout, which cv::FileStorage reads.
#pragma once

#include <string>

#include "frontend/sequence/sequence.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

enum class CalibrationFileKind { kKalibr, kCameraInfo, kEurocSensor, kOpenCv };

const char* CalibrationFileKindName(CalibrationFileKind kind);

// Reads `path`, recognising its kind from its keys: `cam0` (Kalibr), `camera_matrix` with `data`
// (camera_info), `T_BS` (EuRoC sensor.yaml), `!!opencv-matrix` (OpenCV). T_base_camera:
// - Kalibr: base_T_reference * T_cam_imu^-1 (the reference frame is the IMU; without T_cam_imu,
//   a camera-only calibration, base_T_reference itself);
// - EuRoC: base_T_reference * T_BS (the reference frame is the body, B);
// - camera_info (no extrinsics): base_T_reference;
// - OpenCV: the file's own T_base_camera (base_T_reference is not used).
// The odometry noise keys are left at their defaults (not given). Fails with one line naming the
// file and the problem: unreadable or malformed YAML, a missing or malformed key, a camera model
// other than pinhole, a distortion model other than radtan / plumb_bob / radial-tangential /
// equidistant (rational_polynomial is refused), a coefficient count that does not fit the model,
// a non-rigid transform.
Status ReadCalibrationFile(const std::string& path, const Pose3& base_T_reference, Calibration* calibration,
                           CalibrationFileKind* kind = nullptr);

// "tx ty tz qx qy qz qw" (TUM order; the quaternion normalised when within 1e-3 of unit norm) or
// empty (the identity). Fails naming `what` on anything else.
Status ParsePoseText(const std::string& text, const std::string& what, Pose3* pose);

}  // namespace sfm

// TUM trajectory files: each non-comment line is "timestamp tx ty tz qx qy qz qw".
#pragma once

#include <string>
#include <vector>

#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct StampedPose {
  double timestamp = 0;  // seconds
  Pose3 pose;            // a_T_b as the file states it (world_T_base for odometry)
};

// Reads a TUM file. Fails, naming the file and line, on: a missing file, a line that does not hold
// exactly 8 numbers, a non-finite number, a quaternion whose norm is not 1 within 1e-3 (it is
// normalised when within), timestamps that do not increase, and a file with no pose.
Status ReadTumTrajectory(const std::string& path, std::vector<StampedPose>* poses);

// Formats poses as TUM text, one line per pose, with a '#' header line. Each number is the shortest
// text that reads back to the same double, so a write-read round trip is exact.
std::string FormatTumTrajectory(const std::vector<StampedPose>& poses);

// Writes the TUM text atomically (see util/atomic_file.h).
Status WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);

}  // namespace sfm

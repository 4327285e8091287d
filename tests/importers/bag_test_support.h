// Shared by the ROS 2 and ROS 1 bag tests: running a program as a user does, and comparing an
// imported sequence with the generated one its bag was written from.
#pragma once

#include <string>

#include "frontend/sequence/sequence.h"

namespace sfm::testing {

struct AppRun {
  int exit_status = -1;
  std::string errors;  // stderr without glog's informational lines
};

// Runs `binary arguments` through the shell, stderr to a file in `scratch`.
AppRun RunProgram(const std::string& binary, const std::string& arguments, const std::string& scratch);

// Every image bit-identical (grey, or its three equal channels when `colour`), timestamps,
// odometry, ground truth and T_base_camera within 1e-9, K and distortion exact.
void ExpectSameSequence(const Sequence& original, const std::string& imported_dir, bool colour);

}  // namespace sfm::testing

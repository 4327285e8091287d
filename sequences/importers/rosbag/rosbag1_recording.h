// ROS 1 bags (`rosbag record`'s .bag files, format 2.0) as a Recording (recording.h), read with
// Debian's ROS library (rosbag_storage) and its message headers (sensor_msgs, nav_msgs,
// geometry_msgs, tf2_msgs): no bag or message parsing of our own.
#pragma once

#include <string>

#include "sequences/importers/rosbag/bag_importer.h"
#include "util/status.h"

namespace sfm {

// Opens the .bag file and runs ImportRecording on it. A topic whose connection's md5sum differs
// from the compiled message definition's has a `problem` and is refused when chosen; topic types
// are given in ROS 2 spelling ("sensor_msgs/Image" as "sensor_msgs/msg/Image"). Fails, naming the
// file, on a file that rosbag cannot open or read (not a bag, a truncated or corrupt chunk).
Status ImportRosbag1(const std::string& bag_path, const BagImportOptions& options,
                     const std::string& output_dir, BagImportSummary* summary);

}  // namespace sfm

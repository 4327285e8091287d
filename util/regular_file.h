// Reading input files that may be anything a user's path names: a FIFO, a device, a directory, a
// symbolic link loop. Each is named as what it is, and nothing blocks: the type is checked with
// stat before the file is opened, and the open itself is non-blocking.
#pragma once

#include <cstddef>
#include <string>

#include "util/status.h"

namespace sfm {

// Why `path` is not a readable regular file ("does not exist", "is a directory", "is a FIFO (named
// pipe)", "is a character device", "is a symbolic link loop", ...), or "" when it is one.
std::string RegularFileProblem(const std::string& path);

// Reads the whole of the regular file `path` into `contents`. `what` names the file's role in
// messages ("image file", "calibration file"): "<path>: <what> is a FIFO (named pipe), expected a
// regular file". Files larger than `max_bytes` are refused, naming their size.
Status ReadRegularFile(const std::string& path, const std::string& what, std::string* contents,
                       size_t max_bytes = size_t(1) << 31);

}  // namespace sfm

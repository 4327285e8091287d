// Writing output files so that a reader never sees a half-written one: the content goes to a
// temporary file beside the target, which is renamed over the target only once it is complete.
#pragma once

#include <string>

#include "util/status.h"

namespace sfm {

// Writes `contents` to `path` atomically (temporary file in the same directory, then rename).
Status WriteFileAtomically(const std::string& path, const std::string& contents);

// Creates `path` and its parents if needed; fails with a message when it cannot be written to.
Status EnsureWritableDirectory(const std::string& path);

}  // namespace sfm

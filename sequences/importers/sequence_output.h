// The importers' output directory: written whole into a temporary sibling and renamed into place at
// the end, so that a failed import leaves no output (SPEC section 1 directories are read whole).
#pragma once

#include <filesystem>
#include <string>

#include "util/status.h"

namespace sfm {

// Removes the temporary directory unless the import completed and it was renamed into place.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(std::filesystem::path path) : path_(std::move(path)) {}
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  ~TemporaryDirectory() {
    std::error_code ignored;
    if (!released_) std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  void Release() { released_ = true; }

 private:
  std::filesystem::path path_;
  bool released_ = false;
};

// Output path without a trailing separator, so that its parent and name are those of the directory.
std::filesystem::path NormalisedTarget(const std::string& output_dir);

// Checks that `target` can be written (absent, empty, or replaced when `overwrite`) and that its
// parent is a writable directory; returns the temporary sibling to write into (created, empty).
Status PrepareOutputDirectory(const std::filesystem::path& target, bool overwrite,
                              std::filesystem::path* temporary);

// Moves the finished temporary directory to `target`, replacing what is there when allowed.
Status MoveIntoPlace(TemporaryDirectory* temporary, const std::filesystem::path& target);

}  // namespace sfm

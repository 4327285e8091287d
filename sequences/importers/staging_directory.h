// The temporary sibling an importer writes a sequence into: removed when it goes out of scope
// unless the import completed and the directory was renamed into place (Release), so a failed
// import leaves nothing behind.
#pragma once

#include <filesystem>
#include <system_error>
#include <utility>

namespace sfm {

class StagingDirectory {
 public:
  explicit StagingDirectory(std::filesystem::path path) : path_(std::move(path)) {}
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  ~StagingDirectory() {
    std::error_code ignored;
    if (!released_) std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  void Release() { released_ = true; }

 private:
  std::filesystem::path path_;
  bool released_ = false;
};

}  // namespace sfm

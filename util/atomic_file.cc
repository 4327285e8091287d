#include "util/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace sfm {
namespace fs = std::filesystem;

Status WriteFileAtomically(const std::string& path, const std::string& contents) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      return Status::Error(path + ": cannot open for writing (" + std::strerror(errno) + ")");
    }
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      return Status::Error(path + ": write failed (" + std::strerror(errno) + ")");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    return Status::Error(path + ": cannot rename temporary file into place (" + reason + ")");
  }
  return Status::Ok();
}

Status EnsureWritableDirectory(const std::string& path) {
  std::error_code error;
  fs::create_directories(path, error);
  if (error || !fs::is_directory(path)) {
    return Status::Error(path + ": cannot create output directory (" +
                         (error ? error.message() : std::string("not a directory")) + ")");
  }
  if (::access(path.c_str(), W_OK) != 0) {
    return Status::Error(path + ": output directory is not writable (" + std::strerror(errno) + ")");
  }
  return Status::Ok();
}

}  // namespace sfm

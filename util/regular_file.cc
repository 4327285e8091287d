#include "util/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace sfm {
namespace {

const char* TypeProblem(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "is a character device";
  if (S_ISBLK(mode)) return "is a block device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

std::string ErrnoProblem(int error) {
  switch (error) {
    case ENOENT:
      return "does not exist";
    case ELOOP:
      return "is a symbolic link loop";
    case ENOTDIR:
      return "does not exist (a component of the path is not a directory)";
    case EACCES:
      return "cannot be read (permission denied)";
    case ENAMETOOLONG:
      return "has a name too long for the file system";
    default:
      return std::string("cannot be opened (") + std::strerror(error) + ")";
  }
}

}  // namespace

std::string RegularFileProblem(const std::string& path) {
  if (path.find('\0') != std::string::npos) return "holds a NUL character in its name";
  struct stat info;
  if (stat(path.c_str(), &info) != 0) return ErrnoProblem(errno);
  const std::string type = TypeProblem(info.st_mode);
  if (!type.empty()) return type + ", expected a regular file";
  if (access(path.c_str(), R_OK) != 0) return ErrnoProblem(errno);
  return "";
}

Status ReadRegularFile(const std::string& path, const std::string& what, std::string* contents,
                       size_t max_bytes) {
  const std::string prefix = path + ": " + what + " ";
  if (const std::string problem = RegularFileProblem(path); !problem.empty()) {
    return Status::Error(prefix + problem);
  }
  // O_NONBLOCK: should the path have become a FIFO since the stat, the open does not wait for a
  // writer; fstat then names it.
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Status::Error(prefix + ErrnoProblem(errno));
  struct stat info;
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    return Status::Error(prefix + TypeProblem(info.st_mode) + ", expected a regular file");
  }
  if (static_cast<unsigned long long>(info.st_size) > max_bytes) {
    close(fd);
    return Status::Error(prefix + "is " + std::to_string(info.st_size) + " bytes, more than the " +
                         std::to_string(max_bytes) + " accepted");
  }
  contents->clear();
  contents->resize(static_cast<size_t>(info.st_size));
  size_t done = 0;
  while (done < contents->size()) {
    const ssize_t n = read(fd, contents->data() + done, contents->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = std::strerror(errno);
      close(fd);
      return Status::Error(prefix + "cannot be read (" + reason + ")");
    }
    if (n == 0) break;  // the file shrank while being read
    done += static_cast<size_t>(n);
  }
  contents->resize(done);
  close(fd);
  return Status::Ok();
}

}  // namespace sfm

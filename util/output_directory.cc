#include "util/output_directory.h"

#include <dirent.h>
#include <fcntl.h>
#include <glog/logging.h>
#include <signal.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace sfm {
namespace {
namespace fs = std::filesystem;

// ---- Removal with system calls only -------------------------------------------------------------

// Removes everything inside the open directory `dir_fd`. Entries removed while the listing is read
// can shift it, so the listing is read again until a pass finds nothing (at most 64 passes, so an
// entry that cannot be removed does not loop for ever).
bool RemoveContents(int dir_fd, int depth) {
  if (depth > 32) return false;
  alignas(8) char buffer[4096];
  for (int pass = 0; pass < 64; ++pass) {
    if (lseek(dir_fd, 0, SEEK_SET) < 0) return false;
    bool any = false;
    for (;;) {
      const ssize_t n = getdents64(dir_fd, buffer, sizeof(buffer));
      if (n <= 0) break;
      for (ssize_t offset = 0; offset < n;) {
        const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + offset);
        offset += entry->d_reclen;
        const char* name = entry->d_name;
        if (name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))) continue;
        any = true;
        if (unlinkat(dir_fd, name, 0) == 0 || errno == ENOENT) continue;
        if (errno != EISDIR && errno != EPERM) continue;
        const int sub = openat(dir_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (sub >= 0) {
          RemoveContents(sub, depth + 1);
          close(sub);
        }
        unlinkat(dir_fd, name, AT_REMOVEDIR);
      }
    }
    if (!any) return true;
  }
  return false;
}

// ---- State the signal handler reads ------------------------------------------------------------

constexpr int kMaxParents = 16;
struct CleanupState {
  char staging[PATH_MAX];
  char old[PATH_MAX];     // the earlier contents during a fallback swap (no RENAME_EXCHANGE)
  char target[PATH_MAX];  // absolute
  char lock[PATH_MAX];
  char parents[kMaxParents][PATH_MAX];
  char message[PATH_MAX + 128];
  size_t message_length;
  volatile sig_atomic_t parent_count;
  volatile sig_atomic_t lock_held;
  // 0: staging being written; 1: fallback swap, the earlier contents moved to `old`, the new not
  // yet in place; 2: the new contents in place.
  volatile sig_atomic_t phase;
};
CleanupState g_state;
volatile sig_atomic_t g_armed = 0;
const int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

bool CopyPath(const std::string& from, char* to) {
  if (from.size() >= PATH_MAX) return false;
  std::memcpy(to, from.c_str(), from.size() + 1);
  return true;
}

// Async-signal-safe: only system calls on the preformatted paths.
void CleanUp() {
  if (g_state.phase == 1) {
    rename(g_state.old, g_state.target);  // put the earlier contents back
  }
  RemoveTreeNoAlloc(g_state.staging);
  if (g_state.old[0] != '\0') RemoveTreeNoAlloc(g_state.old);
  // The lock file goes before the parents, which it would keep from being empty; the lock itself
  // stays held on its inode until the process ends.
  if (g_state.lock_held) unlink(g_state.lock);
  if (g_state.phase != 2) {
    for (int i = g_state.parent_count - 1; i >= 0; --i) rmdir(g_state.parents[i]);
  }
}

void OnSignal(int signal_number) {
  // Only the main thread writes outputs: handled there, no other thread writes into the staging
  // directory while it is removed (this thread is in the handler, the others never write there).
  if (syscall(SYS_gettid) != getpid()) {
    syscall(SYS_tgkill, getpid(), getpid(), signal_number);
    return;
  }
  if (g_armed) CleanUp();
  if (g_armed && write(STDERR_FILENO, g_state.message, g_state.message_length) < 0) {
    // Nothing more can be done about a stderr that cannot be written.
  }
  _exit(128 + signal_number);
}

// ---- Helpers for Open ---------------------------------------------------------------------------

std::string ErrnoText() { return std::strerror(errno); }

// "<name>.tmp.<digits>": a file an earlier run's WriteFileAtomically left when it was killed.
bool IsLeftover(const std::string& entry, const std::vector<std::string>& names) {
  const size_t tmp = entry.rfind(".tmp.");
  if (tmp == std::string::npos || tmp + 5 == entry.size()) return false;
  if (!std::all_of(entry.begin() + tmp + 5, entry.end(),
                   [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    return false;
  }
  return std::find(names.begin(), names.end(), entry.substr(0, tmp)) != names.end();
}

// Takes the lock file with flock. Another process may have removed the file between our open and
// our flock (it does so at its end, after releasing nothing else): then the path now names another
// file or none, and we try again on the current one.
Status TakeLock(const std::string& target, const std::string& lock_path, int* lock_fd) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
      return Status::Error(target + ": cannot create the lock file " + lock_path + " beside it (" +
                           ErrnoText() + ")");
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const bool busy = errno == EWOULDBLOCK;
      const std::string reason = ErrnoText();
      char pid[32] = {0};
      const ssize_t n = busy ? pread(fd, pid, sizeof(pid) - 1, 0) : 0;
      close(fd);
      if (!busy) return Status::Error(target + ": cannot lock " + lock_path + " (" + reason + ")");
      std::string holder = n > 0 ? std::string(pid, static_cast<size_t>(n)) : "";
      holder.erase(std::remove_if(holder.begin(), holder.end(),
                                  [](char c) { return !std::isdigit(static_cast<unsigned char>(c)); }),
                   holder.end());
      return Status::Error(target + ": another junction_sfm run" +
                           (holder.empty() ? "" : " (pid " + holder + ")") +
                           " is writing this output directory; wait for it or choose another --output");
    }
    struct stat held, current;
    if (fstat(fd, &held) == 0 && stat(lock_path.c_str(), &current) == 0 && held.st_dev == current.st_dev &&
        held.st_ino == current.st_ino) {
      const std::string pid = std::to_string(getpid()) + "\n";
      if (ftruncate(fd, 0) != 0 || pwrite(fd, pid.data(), pid.size(), 0) < 0) {
        // The pid only makes a refusal message more helpful.
      }
      *lock_fd = fd;
      return Status::Ok();
    }
    close(fd);
  }
  return Status::Error(target + ": cannot take the lock " + lock_path + " (it keeps changing)");
}

// The target may be replaced: missing, or a directory holding only what a run writes.
Status CheckReplaceable(const std::string& target, const fs::path& absolute,
                        const std::vector<std::string>& names) {
  struct stat info;
  if (lstat(absolute.c_str(), &info) != 0) {
    if (errno == ENOENT) return Status::Ok();
    return Status::Error(target + ": cannot be examined (" + ErrnoText() + ")");
  }
  if (!S_ISDIR(info.st_mode)) {
    return Status::Error(target + ": exists and is not a directory; the output must be a directory");
  }
  if (access(absolute.c_str(), W_OK | X_OK) != 0) {
    return Status::Error(target + ": output directory is not writable (" + ErrnoText() + ")");
  }
  std::error_code error;
  for (fs::directory_iterator it(absolute, error), end; !error && it != end; it.increment(error)) {
    const std::string entry = it->path().filename().string();
    const bool ours = std::find(names.begin(), names.end(), entry) != names.end();
    if (!ours && !IsLeftover(entry, names)) {
      return Status::Error(
          target + ": holds '" + entry +
          "', which junction_sfm does not write; a run replaces only an empty directory or an "
          "earlier run's output (choose another --output)");
    }
    if (it->is_directory(error) && access(it->path().c_str(), W_OK | X_OK) != 0) {
      return Status::Error(it->path().string() + ": cannot be replaced (" + ErrnoText() + ")");
    }
  }
  if (error) return Status::Error(target + ": cannot be listed (" + error.message() + ")");
  return Status::Ok();
}

}  // namespace

bool RemoveTreeNoAlloc(const char* path) {
  if (unlink(path) == 0 || errno == ENOENT) return true;
  const int fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT;
  RemoveContents(fd, 0);
  close(fd);
  return rmdir(path) == 0 || errno == ENOENT;
}

Status OutputDirectory::Open(const std::string& target, const std::vector<std::string>& output_entries,
                             std::unique_ptr<OutputDirectory>* directory) {
  if (target.empty()) return Status::Error("--output must name a directory");
  if (target.find('\0') != std::string::npos) return Status::Error("--output holds a NUL character");
  std::error_code error;
  fs::path absolute = fs::absolute(target, error);
  if (error) return Status::Error(target + ": cannot make the path absolute (" + error.message() + ")");
  absolute =
      fs::weakly_canonical(absolute, error);  // symbolic links resolved: the swap happens where they point
  if (error) return Status::Error(target + ": cannot resolve the path (" + error.message() + ")");
  if (!absolute.has_filename()) absolute = absolute.parent_path();
  if (absolute == absolute.root_path() || !absolute.has_filename()) {
    return Status::Error(target + ": the root directory cannot be the output directory");
  }
  std::unique_ptr<OutputDirectory> made(new OutputDirectory());
  made->target_ = target;
  made->absolute_ = absolute.string();
  const fs::path parent = absolute.parent_path();
  const std::string name = absolute.filename().string();

  // Missing parents, top-down; removed again if the run does not succeed.
  std::vector<fs::path> missing;
  for (fs::path p = parent; !p.empty() && p != p.root_path(); p = p.parent_path()) {
    struct stat info;
    if (stat(p.c_str(), &info) == 0) {
      if (!S_ISDIR(info.st_mode)) {
        return Status::Error(target + ": cannot create output directory (" + p.string() +
                             " is not a directory)");
      }
      break;
    }
    missing.push_back(p);
  }
  for (auto p = missing.rbegin(); p != missing.rend(); ++p) {
    if (mkdir(p->c_str(), 0777) != 0 && errno != EEXIST) {
      const std::string reason = ErrnoText();
      made->Release(false);
      return Status::Error(target + ": cannot create output directory (" + p->string() + ": " + reason + ")");
    }
    made->created_parents_.push_back(p->string());
  }

  made->lock_path_ = (parent / ("." + name + ".lock")).string();
  if (Status lock = TakeLock(target, made->lock_path_, &made->lock_fd_); !lock.ok()) {
    made->Release(false);
    return lock;
  }
  if (Status replaceable = CheckReplaceable(target, absolute, output_entries); !replaceable.ok()) {
    made->Release(false);
    return replaceable;
  }
  // With the lock held no other run uses a staging directory of this target: any is a killed run's.
  const std::string staging_prefix = "." + name + ".staging-";
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error)) {
    if (it->path().filename().string().rfind(staging_prefix, 0) == 0) RemoveTreeNoAlloc(it->path().c_str());
  }
  std::string staging = (parent / (staging_prefix + "XXXXXX")).string();
  if (mkdtemp(staging.data()) == nullptr) {
    const std::string reason = ErrnoText();
    made->Release(false);
    return Status::Error(target + ": cannot create a directory beside it in " + parent.string() + " (" +
                         reason + ")");
  }
  made->staging_ = staging;
  *directory = std::move(made);
  return Status::Ok();
}

void OutputDirectory::RemoveOnSignals() {
  CHECK(!g_armed) << "one OutputDirectory at a time";
  std::memset(&g_state, 0, sizeof(g_state));
  CHECK(CopyPath(staging_, g_state.staging) && CopyPath(staging_ + ".old", g_state.old) &&
        CopyPath(absolute_, g_state.target) && CopyPath(lock_path_, g_state.lock))
      << "output path too long";
  int count = 0;
  for (const std::string& parent : created_parents_) {
    if (count < kMaxParents && CopyPath(parent, g_state.parents[count])) ++count;
  }
  g_state.parent_count = count;
  g_state.lock_held = lock_fd_ >= 0;
  // A progress line may be on the terminal: clear it first.
  const std::string message = std::string(isatty(STDERR_FILENO) ? "\r\033[K" : "") +
                              std::string(program_invocation_short_name) + ": interrupted; " +
                              target_.substr(0, PATH_MAX) + " is left as it was\n";
  std::memcpy(g_state.message, message.data(), message.size());
  g_state.message_length = message.size();
  g_armed = 1;
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  for (const int s : kSignals) sigaddset(&action.sa_mask, s);  // one cleanup, not one per signal
  for (int i = 0; i < 3; ++i) {
    sigaction(kSignals[i], nullptr, &g_previous[i]);
    // An ignored signal stays ignored (a background job of a script ignores SIGINT, nohup SIGHUP).
    if (g_previous[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &action, nullptr);
  }
}

void OutputDirectory::EmergencyCleanup() {
  if (g_armed) CleanUp();
}

std::string OutputDirectory::UserPath(const std::string& message) const {
  std::string out = message;
  for (size_t at = out.find(staging_); at != std::string::npos; at = out.find(staging_, at)) {
    out.replace(at, staging_.size(), target_);
    at += target_.size();
  }
  return out;
}

Status OutputDirectory::Commit() {
  CHECK(!committed_);
  struct stat info;
  const bool exists = lstat(absolute_.c_str(), &info) == 0;
  if (exists) {
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, absolute_.c_str(), RENAME_EXCHANGE) == 0) {
      g_state.phase = 2;
    } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) {
      // A file system without RENAME_EXCHANGE: two renames; a signal between them puts the earlier
      // contents back (CleanUp, phase 1).
      const std::string old = staging_ + ".old";
      g_state.phase = 1;
      if (rename(absolute_.c_str(), old.c_str()) != 0) {
        g_state.phase = 0;
        return Status::Error(target_ + ": cannot move the earlier output aside (" + ErrnoText() + ")");
      }
      if (rename(staging_.c_str(), absolute_.c_str()) != 0) {
        const std::string reason = ErrnoText();
        rename(old.c_str(), absolute_.c_str());
        g_state.phase = 0;
        return Status::Error(target_ + ": cannot move the new output into place (" + reason + ")");
      }
      g_state.phase = 2;
      RemoveTreeNoAlloc(old.c_str());
    } else {
      return Status::Error(target_ + ": cannot swap the new output into place (" + ErrnoText() + ")");
    }
  } else {
    int moved = renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, absolute_.c_str(), RENAME_NOREPLACE);
    if (moved != 0 && (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP)) {
      moved = rename(staging_.c_str(), absolute_.c_str());
    }
    if (moved != 0)
      return Status::Error(target_ + ": cannot move the new output into place (" + ErrnoText() + ")");
    g_state.phase = 2;
  }
  committed_ = true;
  // The staging path now holds the earlier contents, or nothing.
  if (!RemoveTreeNoAlloc(staging_.c_str())) {
    LOG(WARNING) << staging_ << ": the earlier output could not be removed entirely";
  }
  Release(false);
  return Status::Ok();
}

void OutputDirectory::Release(bool remove_staging) {
  if (remove_staging && !staging_.empty()) RemoveTreeNoAlloc(staging_.c_str());
  // Unlinked while still held, so a run that opened the old file re-checks the path (TakeLock);
  // before the parents, which it would keep from being empty.
  if (lock_fd_ >= 0) unlink(lock_path_.c_str());
  if (!committed_) {
    for (auto p = created_parents_.rbegin(); p != created_parents_.rend(); ++p) rmdir(p->c_str());
  }
  created_parents_.clear();
  if (lock_fd_ >= 0) {
    close(lock_fd_);
    lock_fd_ = -1;
  }
  if (g_armed) {
    g_armed = 0;
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
  }
}

OutputDirectory::~OutputDirectory() {
  if (!committed_) Release(/*remove_staging=*/true);
}

}  // namespace sfm

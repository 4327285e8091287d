// The output directory as one unit (SPEC section 2): a run writes everything into a staging
// directory beside the target, on the same file system, and swaps it into place only when every
// file is complete. A run that fails, throws or is interrupted leaves the earlier directory as it
// was (or no directory where there was none) and no debris; a lock file beside the target refuses
// a second run into the same directory while one is writing.
//
// Layout beside <parent>/<name>:
//   <parent>/.<name>.lock              held (flock) for the whole run, removed at its end
//   <parent>/.<name>.staging-XXXXXX    the new contents; after the swap it holds the old ones,
//                                      which are then removed
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "util/status.h"

namespace sfm {

class OutputDirectory {
 public:
  // Takes the lock and creates the staging directory. `output_entries`: the names a run writes at
  // the top of the directory. An existing target is replaced only when it is a directory that
  // holds nothing but such names (and their "<name>.tmp.<digits>" leftovers): a run replaces its
  // own earlier output, never a directory of the user's. Missing parent directories are created
  // and removed again when the run does not succeed. Staging directories left by a run that was
  // killed (SIGKILL) are removed once the lock is held. Fails with a one-line message naming the
  // directory: it exists and is not a directory, holds other files, its parent cannot be written,
  // or another run holds the lock.
  static Status Open(const std::string& target, const std::vector<std::string>& output_entries,
                     std::unique_ptr<OutputDirectory>* directory);

  // Not committed: removes the staging directory, the parents Open created and the lock.
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::string& target() const { return target_; }    // as given to Open
  const std::string& staging() const { return staging_; }  // where the run writes

  // Swaps the staging directory into place (renameat2 RENAME_EXCHANGE: the target is never
  // missing or mixed), removes the earlier contents and the lock. After success the destructor
  // does nothing.
  Status Commit();

  // From now until Commit returns or this object is destroyed, SIGINT, SIGTERM and SIGHUP (those
  // not ignored when it is called: a script's background job ignores SIGINT) remove
  // the staging directory, the created parents and the lock, print one line on stderr and end the
  // process with status 128 + signal. The handler runs only async-signal-safe system calls
  // (rename, openat, getdents64, unlinkat, write, _exit); a signal that arrives on another
  // thread is passed to the main thread, the only thread that writes the outputs, so nothing
  // is written into the staging directory while it is removed. One OutputDirectory at a time.
  void RemoveOnSignals();

  // The same cleanup for a process that is about to end abnormally (std::terminate, a failed
  // CHECK): removes what the OutputDirectory that RemoveOnSignals was called on has made.
  static void EmergencyCleanup();

  // `message` with the staging path replaced by the target's, so errors name the path a user gave.
  std::string UserPath(const std::string& message) const;

 private:
  OutputDirectory() = default;
  void Release(bool remove_staging);

  std::string target_;     // as given
  std::string absolute_;   // absolute, symbolic links resolved
  std::string staging_;    // absolute
  std::string lock_path_;  // absolute
  int lock_fd_ = -1;
  std::vector<std::string> created_parents_;  // deepest last
  bool committed_ = false;
};

// Removes a directory tree with system calls only (no allocation, async-signal-safe); symbolic
// links are removed, never followed. True when `path` no longer exists.
bool RemoveTreeNoAlloc(const char* path);

}  // namespace sfm

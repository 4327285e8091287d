// Status: the result of an operation that can fail on bad input (a file, a degenerate geometry).
// Programmer errors are CHECKed instead; see docs/design.md.
#pragma once

#include <string>
#include <utility>

namespace sfm {

// [[nodiscard]]: a caller that drops a returned Status is a compiler warning.
class [[nodiscard]] Status {
 public:
  Status() = default;  // OK
  static Status Ok() { return Status(); }
  // A one-line message naming the file (and line) and the problem, e.g.
  // "odometry.txt:12: expected 8 numbers, found 7".
  static Status Error(std::string message) { return Status(std::move(message)); }

  bool ok() const { return !failed_; }
  const std::string& message() const { return message_; }

 private:
  explicit Status(std::string message) : failed_(true), message_(std::move(message)) {}
  bool failed_ = false;
  std::string message_;
};

// Returns early from the calling function with the status when it failed.
#define SFM_RETURN_IF_ERROR(expr)      \
  do {                                 \
    ::sfm::Status sfm_status_ = (expr); \
    if (!sfm_status_.ok()) return sfm_status_; \
  } while (false)

}  // namespace sfm

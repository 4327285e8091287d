#include "frontend/geometry/tum_io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/util/atomic_file.h"
#include "frontend/util/number_text.h"

namespace sfm {
namespace {

constexpr int kNumbersPerLine = 8;
constexpr double kQuaternionNormTolerance = 1e-3;
// A quaternion read back from our own %.17g output is unit to rounding; renormalising it would
// change its last bits and break exact round trips, so only norms further off are corrected.
constexpr double kRenormaliseAbove = 1e-14;

// Parses a whole token as a double; false when it is not entirely a number.
bool ParseDouble(const std::string& token, double* value) {
  errno = 0;
  char* end = nullptr;
  *value = std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0' && errno != ERANGE;
}

}  // namespace

Status ReadTumTrajectory(const std::string& path, std::vector<StampedPose>* poses) {
  poses->clear();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    return Status::Error(path + ": is a directory, expected a TUM trajectory file");
  }
  std::ifstream in(path);
  if (!in) return Status::Error(path + ": cannot open (" + std::strerror(errno) + ")");

  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    const size_t comment = line.find('#');
    if (comment != std::string::npos) line.resize(comment);
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string word; tokens >> word;) words.push_back(word);
    if (words.empty()) continue;
    if (static_cast<int>(words.size()) != kNumbersPerLine) {
      return Status::Error(where + "expected 8 numbers (timestamp tx ty tz qx qy qz qw), found " +
                           std::to_string(words.size()));
    }
    double v[kNumbersPerLine];
    for (int i = 0; i < kNumbersPerLine; ++i) {
      if (!ParseDouble(words[i], &v[i])) {
        return Status::Error(where + "'" + words[i] + "' is not a number (field " + std::to_string(i + 1) +
                             " of timestamp tx ty tz qx qy qz qw)");
      }
      if (!std::isfinite(v[i])) {
        return Status::Error(where + "non-finite number '" + words[i] + "' (field " + std::to_string(i + 1) +
                             " of timestamp tx ty tz qx qy qz qw)");
      }
    }
    StampedPose stamped;
    stamped.timestamp = v[0];
    if (!poses->empty() && !(stamped.timestamp > poses->back().timestamp)) {
      return Status::Error(where + "timestamp " + ShortestNumberText(stamped.timestamp) +
                           " does not increase (previous line has " + ShortestNumberText(poses->back().timestamp) +
                           ")");
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // Eigen's constructor takes w first
    const double norm = q.norm();
    if (std::abs(norm - 1) > kQuaternionNormTolerance) {
      return Status::Error(where + "quaternion qx qy qz qw has norm " + ShortestNumberText(norm) +
                           ", expected 1 (within 1e-3)");
    }
    if (std::abs(norm - 1) > kRenormaliseAbove) q.normalize();
    stamped.pose = Pose3(q, Eigen::Vector3d(v[1], v[2], v[3]));
    poses->push_back(stamped);
  }
  if (in.bad()) return Status::Error(path + ": read error (" + std::strerror(errno) + ")");
  if (poses->empty()) return Status::Error(path + ": no pose (the file holds no data line)");
  return Status::Ok();
}

std::string FormatTumTrajectory(const std::vector<StampedPose>& poses) {
  std::string text = "# timestamp tx ty tz qx qy qz qw\n";
  for (const StampedPose& p : poses) {
    const Eigen::Vector3d& t = p.pose.translation;
    const Eigen::Quaterniond& q = p.pose.rotation;
    for (double value : {p.timestamp, t.x(), t.y(), t.z(), q.x(), q.y(), q.z()}) {
      text += ShortestNumberText(value);
      text += ' ';
    }
    text += ShortestNumberText(q.w());
    text += '\n';
  }
  return text;
}

Status WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  return WriteFileAtomically(path, FormatTumTrajectory(poses));
}

}  // namespace sfm

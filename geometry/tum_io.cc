#include "geometry/tum_io.h"

#include <cmath>
#include <cstdio>

#include "util/atomic_file.h"
#include "util/number_text.h"
#include "util/text_file.h"

namespace sfm {
namespace {

constexpr int kNumbersPerLine = 8;
constexpr double kQuaternionNormTolerance = 1e-3;
// A quaternion read back from our own %.17g output is unit to rounding; renormalising it would
// change its last bits and break exact round trips, so only norms further off are corrected.
constexpr double kRenormaliseAbove = 1e-14;

}  // namespace

Status ReadTumTrajectory(const std::string& path, std::vector<StampedPose>* poses) {
  poses->clear();
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  for (const DataLine& line : lines) {
    const std::string& where = line.where;
    const std::vector<std::string> words = SplitWords(line.text);
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

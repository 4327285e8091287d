#include "sequences/importers/euroc_importer.h"

#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <glog/logging.h>

#include "frontend/sequence/image_header.h"
#include "sequences/importers/calibration_files.h"
#include "sequences/importers/sequence_output.h"
#include "util/atomic_file.h"
#include "util/number_text.h"
#include "util/regular_file.h"
#include "util/text_file.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

// SPEC section 1: a pose within 1 ms of an image's time is the image's.
constexpr double kAssociationTolerance = 1e-3;

// The comma-separated fields of an ASL CSV line, white space trimmed.
std::vector<std::string> CsvFields(const std::string& text) {
  std::vector<std::string> fields;
  size_t at = 0;
  while (true) {
    const size_t comma = std::min(text.find(',', at), text.size());
    std::string field = text.substr(at, comma - at);
    const size_t first = field.find_first_not_of(" \t\r"), last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
    if (comma == text.size()) break;
    at = comma + 1;
  }
  return fields;
}

// An ASL timestamp (integer nanoseconds) in seconds.
bool ParseNanoseconds(const std::string& text, double* seconds) {
  if (text.empty() || text.size() > 19 || !std::all_of(text.begin(), text.end(), ::isdigit)) return false;
  const long long ns = std::stoll(text);
  *seconds = static_cast<double>(ns / 1000000000) + static_cast<double>(ns % 1000000000) * 1e-9;
  return true;
}

Status ReadAslTrajectory(const std::string& path, const std::vector<DataLine>& lines,
                         std::vector<StampedPose>* poses) {
  poses->clear();
  for (const DataLine& line : lines) {
    const std::vector<std::string> fields = CsvFields(line.text);
    double v[8];
    bool ok = fields.size() >= 8 && ParseNanoseconds(fields[0], &v[0]);
    for (int i = 1; ok && i < 8; ++i) ok = ParseDouble(fields[i], &v[i]) && std::isfinite(v[i]);
    if (!ok) {
      return Status::Error(line.where +
                           ": expected 'timestamp [ns],x,y,z,qw,qx,qy,qz' (ASL CSV), found '" + line.text + "'");
    }
    const Eigen::Quaterniond q(v[4], v[5], v[6], v[7]);
    if (std::abs(q.norm() - 1) > 1e-3) {
      return Status::Error(line.where + ": quaternion norm " + ShortestNumberText(q.norm()) + " is not 1");
    }
    if (!poses->empty() && !(v[0] > poses->back().timestamp)) {
      return Status::Error(line.where + ": timestamp does not increase");
    }
    poses->push_back({v[0], Pose3(q.normalized(), Eigen::Vector3d(v[1], v[2], v[3]))});
  }
  if (poses->empty()) return Status::Error(path + ": holds no pose");
  return Status::Ok();
}

std::string NotesText(const RecordedSequence& sequence) {
  std::string text = "# How this sequence was imported (import_sequence)\n";
  for (const std::string& note : sequence.notes) text += note + "\n";
  return text;
}

}  // namespace

Status ReadTrajectoryFile(const std::string& path, std::vector<StampedPose>* poses) {
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  if (lines.empty()) return Status::Error(path + ": holds no pose");
  if (lines.front().text.find(',') != std::string::npos) return ReadAslTrajectory(path, lines, poses);
  return ReadTumTrajectory(path, poses);
}

bool TrajectoryPoseAt(const std::vector<StampedPose>& poses, double t, Pose3* pose) {
  if (poses.empty()) return false;
  const auto after = std::lower_bound(poses.begin(), poses.end(), t,
                                      [](const StampedPose& p, double time) { return p.timestamp < time; });
  // The nearest sample within the tolerance.
  const StampedPose* nearest = nullptr;
  if (after != poses.end()) nearest = &*after;
  if (after != poses.begin() && (nearest == nullptr || t - (after - 1)->timestamp < nearest->timestamp - t)) {
    nearest = &*(after - 1);
  }
  if (std::abs(nearest->timestamp - t) <= kAssociationTolerance) {
    *pose = nearest->pose;
    return true;
  }
  if (after == poses.begin() || after == poses.end()) return false;
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  *pose = InterpolatePose(a.pose, b.pose, (t - a.timestamp) / (b.timestamp - a.timestamp));
  return true;
}

Status ReadEurocSequence(const std::string& input_dir, const EurocImportOptions& options,
                         RecordedSequence* sequence) {
  const fs::path root(input_dir);
  std::error_code error;
  if (!fs::is_directory(root, error)) return Status::Error(input_dir + ": is not a directory (an ASL folder)");
  if (options.odometry_path.empty()) {
    return Status::Error(input_dir +
                         ": an ASL folder holds no wheel odometry; name the robot's odometry file (TUM or ASL "
                         "CSV) with --odometry");
  }
  *sequence = RecordedSequence();
  const std::string calibration_path =
      options.calibration_path.empty() ? (root / "cam0" / "sensor.yaml").string() : options.calibration_path;
  CalibrationFileKind kind;
  SFM_RETURN_IF_ERROR(ReadCalibrationFile(calibration_path, options.base_T_body, &sequence->calibration, &kind));
  sequence->notes.push_back("calibration: " + calibration_path + " (" + CalibrationFileKindName(kind) + ")");

  const std::string list_path = (root / "cam0" / "data.csv").string();
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(list_path, &lines));
  std::vector<StampedPose> odometry, groundtruth;
  SFM_RETURN_IF_ERROR(ReadTrajectoryFile(options.odometry_path, &odometry));
  sequence->notes.push_back("odometry: " + options.odometry_path + " (world_T_base, at each image's time)");
  const std::string groundtruth_path = (root / "state_groundtruth_estimate0" / "data.csv").string();
  const bool has_groundtruth = fs::exists(groundtruth_path, error);
  if (has_groundtruth) {
    SFM_RETURN_IF_ERROR(ReadTrajectoryFile(groundtruth_path, &groundtruth));
    sequence->notes.push_back("ground truth: " + groundtruth_path + " (world_T_body * base_T_body^-1)");
  }
  int outside_groundtruth = 0;
  double previous = -1;
  for (const DataLine& line : lines) {
    const std::vector<std::string> fields = CsvFields(line.text);
    RecordedFrame frame;
    if (fields.size() != 2 || !ParseNanoseconds(fields[0], &frame.timestamp) || fields[1].empty()) {
      return Status::Error(line.where + ": expected 'timestamp [ns],filename', found '" + line.text + "'");
    }
    if (!(frame.timestamp > previous)) return Status::Error(line.where + ": timestamp does not increase");
    previous = frame.timestamp;
    frame.source_image = (root / "cam0" / "data" / fields[1]).string();
    const std::string problem = RegularFileProblem(frame.source_image);
    if (!problem.empty()) return Status::Error(line.where + ": image " + frame.source_image + " " + problem);
    if (!TrajectoryPoseAt(odometry, frame.timestamp, &frame.world_T_base_odometry)) {
      const bool before = frame.timestamp < odometry.front().timestamp;
      return Status::Error(options.odometry_path + ": the odometry " +
                           (before ? "starts at " + ShortestNumberText(odometry.front().timestamp) + " s, after"
                                   : "ends at " + ShortestNumberText(odometry.back().timestamp) + " s, before") +
                           " the image at " + ShortestNumberText(frame.timestamp) + " s (" + line.where + ")");
    }
    if (has_groundtruth) {
      Pose3 world_T_body;
      if (!TrajectoryPoseAt(groundtruth, frame.timestamp, &world_T_body)) {
        ++outside_groundtruth;
        continue;
      }
      frame.world_T_base_groundtruth = world_T_body * options.base_T_body.Inverse();
    }
    sequence->frames.push_back(frame);
  }
  if (outside_groundtruth > 0) {
    LOG(INFO) << groundtruth_path << ": " << outside_groundtruth
              << " images outside the ground truth's time span are left out";
    sequence->notes.push_back(std::to_string(outside_groundtruth) +
                              " images outside the ground truth's time span left out");
  }
  if (sequence->frames.size() < 2) {
    return Status::Error(list_path + ": fewer than 2 images left (" + std::to_string(sequence->frames.size()) +
                         ", " + std::to_string(outside_groundtruth) + " outside the ground truth's time span)");
  }
  return Status::Ok();
}

Status WriteRecordedSequence(const RecordedSequence& sequence, const std::string& output_dir, bool overwrite) {
  const fs::path target = NormalisedTarget(output_dir);
  fs::path temporary;
  SFM_RETURN_IF_ERROR(PrepareOutputDirectory(target, overwrite, &temporary));
  TemporaryDirectory staging(temporary);
  SFM_RETURN_IF_ERROR(EnsureWritableDirectory((staging.path() / "images").string()));

  const Camera& camera = sequence.calibration.camera;
  std::string images_text = "# timestamp image\n";
  std::vector<StampedPose> odometry, groundtruth;
  bool every_groundtruth = true;
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    const RecordedFrame& frame = sequence.frames[i];
    std::string data;
    SFM_RETURN_IF_ERROR(ReadRegularFile(frame.source_image, "image file", &data, size_t(1) << 30));
    const ImageHeader header = ReadImageHeader(data);
    if (header.format.empty() || !header.problem.empty()) {
      return Status::Error(frame.source_image + ": not a readable PNG, JPEG or PNM image" +
                           (header.problem.empty() ? "" : " (" + header.problem + ")"));
    }
    if (header.width != camera.width || header.height != camera.height) {
      return Status::Error(frame.source_image + ": image is " + std::to_string(header.width) + "x" +
                           std::to_string(header.height) + ", the calibration's " + std::to_string(camera.width) +
                           "x" + std::to_string(camera.height));
    }
    char name[32];
    std::snprintf(name, sizeof(name), "images/%06zu", i);
    const std::string relative = name + fs::path(frame.source_image).extension().string();
    SFM_RETURN_IF_ERROR(WriteFileAtomically((staging.path() / relative).string(), data));
    images_text += ShortestNumberText(frame.timestamp) + " " + relative + "\n";
    odometry.push_back({frame.timestamp, frame.world_T_base_odometry});
    every_groundtruth = every_groundtruth && frame.world_T_base_groundtruth.has_value();
    if (frame.world_T_base_groundtruth) groundtruth.push_back({frame.timestamp, *frame.world_T_base_groundtruth});
  }
  const fs::path& root = staging.path();
  SFM_RETURN_IF_ERROR(WriteCalibration((root / "sequence.yaml").string(), sequence.calibration));
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "images.txt").string(), images_text));
  SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "odometry.txt").string(), odometry));
  if (every_groundtruth) SFM_RETURN_IF_ERROR(WriteTumTrajectory((root / "groundtruth.txt").string(), groundtruth));
  SFM_RETURN_IF_ERROR(WriteFileAtomically((root / "import_notes.txt").string(), NotesText(sequence)));

  return MoveIntoPlace(&staging, target);
}

}  // namespace sfm

#include "frontend/sequence/sequence.h"

#include <glog/logging.h>
#include <sys/stat.h>

#include <Eigen/LU>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "geometry/tum_io.h"
#include "frontend/sequence/image_header.h"
#include "util/atomic_file.h"
#include "util/json_format.h"
#include "util/number_text.h"
#include "util/regular_file.h"
#include "util/text_file.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

// T_base_camera's rotation block must satisfy |R^T R - I| below this (files hold ~6+ digits).
constexpr double kRotationTolerance = 1e-5;
// Timestamps are read from decimal text, so a difference of exactly 1 ms may come out a hair over:
// by up to a few ulps of the timestamp, ~1e-7 s for Unix times (1.6e9 s).
double TimestampSlack(double timestamp) {
  return 1e-9 + 4 * std::numeric_limits<double>::epsilon() * std::abs(timestamp);
}

// OpenCV's messages can span lines; ours must not.
std::string OneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

bool ParseFiniteDouble(const std::string& token, double* value) {
  return ParseDouble(token, value) && std::isfinite(*value);
}

// The largest image side accepted (pixels): beyond any camera, and width * height * 3 bytes stay
// far inside the int OpenCV sizes its buffers with.
constexpr long long kMaxImageSide = 100000;
// T_base_camera's translation (metres) and the odometry sigmas are bounded so that their squares
// and products with poses stay finite; no robot's camera sits a thousand kilometres from its base.
constexpr double kMaxBaseCameraTranslationM = 1e6;
constexpr double kMaxOdometrySigma = 1e6;

// The text after "<key>:" on the line that starts with the top-level key, '#' comment and white
// space cut; "" when there is no such line. OpenCV stores a YAML integer in an int without
// reporting overflow (4294967936 reads as 640), so integer keys are range-checked on this text.
std::string RawTopLevelValue(const std::string& text, const std::string& key) {
  for (size_t at = 0; at < text.size();) {
    const size_t end = std::min(text.find('\n', at), text.size());
    if (text.compare(at, key.size(), key) == 0) {
      size_t colon = at + key.size();
      while (colon < end && (text[colon] == ' ' || text[colon] == '\t')) ++colon;
      if (colon < end && text[colon] == ':') {
        std::string value = text.substr(colon + 1, end - colon - 1);
        const size_t comment = value.find('#');
        if (comment != std::string::npos) value.resize(comment);
        const size_t first = value.find_first_not_of(" \t\r");
        if (first == std::string::npos) return "";
        const size_t last = value.find_last_not_of(" \t\r");
        return value.substr(first, last - first + 1);
      }
    }
    at = end + 1;
  }
  return "";
}

// Reads sequence.yaml's keys; cv::Exception from OpenCV propagates to ReadCalibration.
class CalibrationReader {
 public:
  CalibrationReader(const std::string& path, const std::string& text, const cv::FileStorage& storage)
      : path_(path), text_(text), storage_(storage) {}

  // A positive integer of at most `max`, range-checked on the file's own text (RawTopLevelValue).
  Status PositiveInt(const std::string& key, long long max, int* value) const {
    const cv::FileNode node = storage_[key];
    if (node.empty() || node.isNone()) return Missing(key);
    if (!node.isInt()) return Error(key, "must be an integer");
    const std::string raw = RawTopLevelValue(text_, key);
    if (!raw.empty()) {
      errno = 0;
      char* end = nullptr;
      const long long read = std::strtoll(raw.c_str(), &end, 10);
      if (end != raw.c_str() && (errno == ERANGE || read > max || read < -max)) {
        return Error(key, "is " + raw + ", out of range (at most " + std::to_string(max) + ")");
      }
    }
    *value = static_cast<int>(node);
    if (*value <= 0) return Error(key, "must be positive, found " + std::to_string(*value));
    if (*value > max)
      return Error(key,
                   "is " + std::to_string(*value) + ", out of range (at most " + std::to_string(max) + ")");
    return Status::Ok();
  }

  // An optional positive real; *present says whether the key was there.
  Status OptionalPositiveReal(const std::string& key, double* value, bool* present) const {
    const cv::FileNode node = storage_[key];
    *present = !(node.empty() || node.isNone());
    if (!*present) return Status::Ok();
    if (!node.isReal() && !node.isInt()) return Error(key, "must be a number");
    const double read = static_cast<double>(node);
    if (!std::isfinite(read)) return Error(key, "is not finite (" + ShortestNumberText(read) + ")");
    if (read <= 0) return Error(key, "must be positive, found " + ShortestNumberText(read));
    if (read > kMaxOdometrySigma) {
      return Error(key, "is " + ShortestNumberText(read) + ", out of range (at most " +
                            ShortestNumberText(kMaxOdometrySigma) + ")");
    }
    *value = read;
    return Status::Ok();
  }

  // The optional lens model (SPEC section 1); radtan when the key is absent.
  Status OptionalDistortionModel(const std::string& key, DistortionModel* model) const {
    *model = DistortionModel::kRadTan;
    const cv::FileNode node = storage_[key];
    if (node.empty() || node.isNone()) return Status::Ok();
    if (!node.isString()) return Error(key, "must be radtan or equidistant");
    const std::string name = node.string();
    if (!ParseDistortionModel(name, model)) {
      return Error(key, "is '" + name + "', not a known model (radtan or equidistant)");
    }
    return Status::Ok();
  }

  // A matrix of one of the allowed shapes (rows x cols), as CV_64F with finite entries. `what`
  // follows the first shape in the message on a wrong shape.
  Status Matrix(const std::string& key, const std::vector<std::pair<int, int>>& shapes, cv::Mat* matrix,
                const std::string& what = "") const {
    const std::string expected =
        std::to_string(shapes[0].first) + "x" + std::to_string(shapes[0].second) + what;
    const cv::FileNode node = storage_[key];
    if (node.empty() || node.isNone()) return Missing(key);
    if (!node.isMap() || node["rows"].empty() || node["cols"].empty() || node["data"].empty()) {
      return Error(key, "must be a " + expected + " !!opencv-matrix (with rows, cols, dt, data)");
    }
    cv::Mat read;
    try {
      node >> read;
    } catch (const cv::Exception& e) {
      return Error(key, "is not a valid !!opencv-matrix (" + OneLine(e.err) + ")");
    }
    if (read.empty()) return Error(key, "must be a " + expected + " !!opencv-matrix, found an empty matrix");
    if (read.channels() != 1) return Error(key, "must be a single-channel matrix");
    const bool shape_ok = std::any_of(shapes.begin(), shapes.end(), [&](const std::pair<int, int>& s) {
      return read.rows == s.first && read.cols == s.second;
    });
    if (!shape_ok) {
      return Error(key, "must be " + expected + ", found " + std::to_string(read.rows) + "x" +
                            std::to_string(read.cols));
    }
    read.convertTo(*matrix, CV_64F);
    for (int r = 0; r < matrix->rows; ++r) {
      for (int c = 0; c < matrix->cols; ++c) {
        const double value = matrix->at<double>(r, c);
        if (!std::isfinite(value)) {
          return Error(key, "entry (" + std::to_string(r) + "," + std::to_string(c) + ") is not finite (" +
                                ShortestNumberText(value) + ")");
        }
      }
    }
    return Status::Ok();
  }

  Status Error(const std::string& key, const std::string& problem) const {
    return Status::Error(path_ + ": key '" + key + "' " + problem);
  }

 private:
  Status Missing(const std::string& key) const {
    return Status::Error(path_ + ": missing key '" + key + "'");
  }

  const std::string& path_;
  const std::string& text_;
  const cv::FileStorage& storage_;
};

Status ReadCalibrationKeys(const std::string& path, const std::string& text, const cv::FileStorage& storage,
                           Calibration* calibration) {
  const CalibrationReader reader(path, text, storage);
  Camera& camera = calibration->camera;
  SFM_RETURN_IF_ERROR(reader.PositiveInt("image_width", kMaxImageSide, &camera.width));
  SFM_RETURN_IF_ERROR(reader.PositiveInt("image_height", kMaxImageSide, &camera.height));

  cv::Mat K;
  SFM_RETURN_IF_ERROR(reader.Matrix("camera_matrix", {{3, 3}}, &K));
  if (K.at<double>(0, 1) != 0 || K.at<double>(1, 0) != 0 || K.at<double>(2, 0) != 0 ||
      K.at<double>(2, 1) != 0 || K.at<double>(2, 2) != 1) {
    return reader.Error("camera_matrix", "must have the form (fx 0 cx; 0 fy cy; 0 0 1): the camera model has no skew");
  }
  camera.fx = K.at<double>(0, 0);
  camera.fy = K.at<double>(1, 1);
  camera.cx = K.at<double>(0, 2);
  camera.cy = K.at<double>(1, 2);
  if (camera.fx <= 0 || camera.fy <= 0) {
    return reader.Error("camera_matrix", "must have positive focal lengths, found fx " + ShortestNumberText(camera.fx) +
                                             ", fy " + ShortestNumberText(camera.fy));
  }

  SFM_RETURN_IF_ERROR(reader.OptionalDistortionModel("distortion_model", &camera.model));
  cv::Mat distortion;
  // OpenCV's own calibration writes either orientation; Kalibr's radtan has no k3 (SPEC section 1).
  if (camera.model == DistortionModel::kEquidistant) {
    SFM_RETURN_IF_ERROR(reader.Matrix("distortion_coefficients", {{1, 4}, {4, 1}}, &distortion,
                                      " (k1 k2 k3 k4 of distortion_model equidistant)"));
  } else {
    SFM_RETURN_IF_ERROR(reader.Matrix("distortion_coefficients", {{1, 5}, {5, 1}, {1, 4}, {4, 1}},
                                      &distortion,
                                      " (k1 k2 p1 p2 k3) or 1x4 (k1 k2 p1 p2) for distortion_model radtan"));
  }
  camera.distortion = {0, 0, 0, 0, 0};
  for (int i = 0; i < static_cast<int>(distortion.total()); ++i)
    camera.distortion[i] = distortion.at<double>(i);

  cv::Mat T;
  SFM_RETURN_IF_ERROR(reader.Matrix("T_base_camera", {{4, 4}}, &T));
  Eigen::Matrix4d base_T_camera;
  cv::cv2eigen(T, base_T_camera);
  if ((base_T_camera.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > kRotationTolerance) {
    return reader.Error("T_base_camera", "must have last row 0 0 0 1");
  }
  const Eigen::Matrix3d R = base_T_camera.topLeftCorner<3, 3>();
  const double orthogonality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  const double determinant = R.determinant();
  if (orthogonality_error > kRotationTolerance || determinant <= 0) {
    return reader.Error("T_base_camera", "rotation part is not a rotation (|R^T R - I| = " +
                                             ShortestNumberText(orthogonality_error) + ", det R = " +
                                             ShortestNumberText(determinant) + ")");
  }
  const double translation = base_T_camera.topRightCorner<3, 1>().cwiseAbs().maxCoeff();  // no overflow
  if (!(translation <= kMaxBaseCameraTranslationM)) {
    return reader.Error("T_base_camera", "translation has a coordinate of " +
                                             ShortestNumberText(translation) + " m, out of range (at most " +
                                             ShortestNumberText(kMaxBaseCameraTranslationM) + " m)");
  }
  calibration->base_T_camera = Pose3::FromMatrix4(base_T_camera);

  bool translation_given = false, rotation_given = false;
  calibration->odometry_noise = OdometryNoise();
  SFM_RETURN_IF_ERROR(reader.OptionalPositiveReal(
      "odometry_translation_sigma", &calibration->odometry_noise.translation_sigma, &translation_given));
  SFM_RETURN_IF_ERROR(reader.OptionalPositiveReal(
      "odometry_rotation_sigma", &calibration->odometry_noise.rotation_sigma, &rotation_given));
  calibration->odometry_noise_given = translation_given && rotation_given;
  return Status::Ok();
}

// ":<line>: malformed YAML (<what>)" from an OpenCV parser exception. OpenCV 4.6 puts the parser's
// "<file>(<line>): <what>" in Exception::func rather than ::err, so both are looked at.
std::string DescribeYamlError(const cv::Exception& e, int lines_added) {
  if (e.code == cv::Error::StsParseError) {
    for (const std::string& text : {e.func, e.err}) {
      const size_t open = text.find('('), close = text.find("): ");
      if (open == std::string::npos || close == std::string::npos || close < open) continue;
      const int line = std::atoi(text.substr(open + 1, close - open - 1).c_str()) - lines_added;
      return ":" + std::to_string(line) + ": malformed YAML (" + OneLine(text.substr(close + 3)) + ")";
    }
  }
  return ": malformed YAML (" + OneLine(e.err) + ")";
}

// A difference of two decimal timestamps for a message: "%.6g" gives "0.05" where the exact double
// would read "0.04999999999999893".
std::string DurationText(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", seconds);
  return text;
}

// How an image's pose was taken from a trajectory file.
enum class Association { kNearest, kInterpolated, kOutsideSpan };

// The trajectory's pose at `timestamp` (poses in strictly increasing time, as ReadTumTrajectory
// guarantees). A line within kTimestampTolerance is used as is (the nearest, when two are), so
// trajectories stamped like the images give their own poses bit for bit. Otherwise, when the time
// lies between two lines, the pose is interpolated between them: linear in translation, slerp
// (shortest arc) in rotation, i.e. constant velocity between the two lines. *gap is then their time
// difference. Beyond the first or last line by more than the tolerance there is nothing to
// interpolate from and nothing is extrapolated: kOutsideSpan.
Association PoseAtTime(const std::vector<StampedPose>& poses, double timestamp, Pose3* pose, double* gap) {
  const auto after = std::lower_bound(poses.begin(), poses.end(), timestamp,
                                      [](const StampedPose& p, double t) { return p.timestamp < t; });
  auto nearest = poses.end();
  double nearest_difference = std::numeric_limits<double>::infinity();
  for (auto it : {after - (after == poses.begin() ? 0 : 1), after}) {
    if (it == poses.end()) continue;
    const double difference = std::abs(it->timestamp - timestamp);
    if (difference < nearest_difference) {
      nearest_difference = difference;
      nearest = it;
    }
  }
  *gap = 0;
  if (nearest_difference <= kTimestampTolerance + TimestampSlack(timestamp)) {
    *pose = nearest->pose;
    return Association::kNearest;
  }
  // No line within the tolerance, so none equals `timestamp`: `after` is the first line later than
  // it, and an image inside the span has one line on either side.
  if (after == poses.begin() || after == poses.end()) return Association::kOutsideSpan;
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  *gap = b.timestamp - a.timestamp;
  const double s = (timestamp - a.timestamp) / *gap;  // in (0, 1)
  *pose = InterpolatePose(a.pose, b.pose, s);
  return Association::kInterpolated;
}

// Associates each frame with a pose of one trajectory file (odometry.txt or groundtruth.txt) and
// stores it through `store`. Interpolation is said once per file in the log, not once per frame.
template <typename Store>
Status AssociatePoses(const std::string& images_path, const std::vector<int>& line_numbers,
                      const std::string& trajectory_path, const std::vector<StampedPose>& poses,
                      std::vector<Frame>* frames, Store store) {
  int interpolated = 0;
  double widest_gap = 0;
  for (size_t i = 0; i < frames->size(); ++i) {
    Frame& frame = (*frames)[i];
    Pose3 pose;
    double gap = 0;
    const Association association = PoseAtTime(poses, frame.timestamp, &pose, &gap);
    if (association == Association::kOutsideSpan) {
      const bool before = frame.timestamp < poses.front().timestamp;
      const double end = before ? poses.front().timestamp : poses.back().timestamp;
      return Status::Error(images_path + ":" + std::to_string(line_numbers[i]) + ": timestamp " +
                           ShortestNumberText(frame.timestamp) + " is outside the time span of " + trajectory_path +
                           " (" + ShortestNumberText(poses.front().timestamp) + " to " +
                           ShortestNumberText(poses.back().timestamp) + " s): " +
                           DurationText(std::abs(frame.timestamp - end)) + " s " +
                           (before ? "before its first" : "after its last") +
                           " pose, more than the 1 ms tolerance");
    }
    if (association == Association::kInterpolated) {
      ++interpolated;
      widest_gap = std::max(widest_gap, gap);
    }
    store(&frame, pose);
  }
  if (interpolated > 0) {
    LOG(INFO) << trajectory_path << ": " << interpolated << " of " << frames->size()
              << " images have no pose within 1 ms; their poses are interpolated between the two lines "
                 "around them (translation linear, rotation slerp; widest gap "
              << DurationText(widest_gap) << " s)";
  }
  return Status::Ok();
}

Status ReadImageList(const std::string& directory, const std::string& path, std::vector<Frame>* frames,
                     std::vector<int>* line_numbers) {
  std::vector<DataLine> lines;
  SFM_RETURN_IF_ERROR(ReadDataLines(path, &lines));
  for (const DataLine& line : lines) {
    const std::string& where = line.where;
    std::istringstream words(line.text);
    std::string timestamp_text;
    words >> timestamp_text;
    std::string image_path;
    std::getline(words >> std::ws, image_path);
    while (!image_path.empty() && std::isspace(static_cast<unsigned char>(image_path.back()))) image_path.pop_back();
    Frame frame;
    if (!ParseFiniteDouble(timestamp_text, &frame.timestamp) || image_path.empty()) {
      return Status::Error(where + "expected '<timestamp> <relative image path>', found '" + OneLine(line.text) + "'");
    }
    if (!frames->empty() && !(frame.timestamp > frames->back().timestamp)) {
      return Status::Error(where + "timestamp " + ShortestNumberText(frame.timestamp) +
                           " is not after the previous frame's " + ShortestNumberText(frames->back().timestamp) +
                           " (frames must be in increasing time order)");
    }
    if (!IsValidUtf8(image_path)) {
      return Status::Error(where + "the image path is not valid UTF-8; rename the image with a UTF-8 name");
    }
    const fs::path image_file = fs::path(directory) / image_path;
    if (const std::string problem = RegularFileProblem(image_file.string()); !problem.empty()) {
      return Status::Error(where + "image file " + image_file.string() + " " + problem);
    }
    frame.index = static_cast<int>(frames->size());
    frame.image_path = image_path;
    frames->push_back(frame);
    line_numbers->push_back(line.number);
  }
  if (frames->empty()) return Status::Error(path + ": lists no image");
  if (frames->size() < 2) {
    return Status::Error(path + ": lists " + std::to_string(frames->size()) +
                         " frame, at least 2 are needed");
  }
  return Status::Ok();
}

}  // namespace

Status ReadCalibration(const std::string& yaml_path, Calibration* calibration) {
  std::string text;
  SFM_RETURN_IF_ERROR(ReadRegularFile(yaml_path, "calibration file", &text, size_t(1) << 24));
  SFM_RETURN_IF_ERROR(CheckPlainText(yaml_path, text));
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) return Status::Error(yaml_path + ": file is empty");
  // OpenCV 4.6 rejects YAML without its "%YAML" directive; hand-written and PyYAML files lack it.
  const bool header_added = text.rfind("%YAML", 0) != 0;
  if (header_added) text = "%YAML:1.0\n" + text;
  try {
    const cv::FileStorage storage(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!storage.isOpened()) return Status::Error(yaml_path + ": cannot be parsed as OpenCV YAML");
    return ReadCalibrationKeys(yaml_path, text, storage, calibration);
  } catch (const cv::Exception& e) {
    return Status::Error(yaml_path + DescribeYamlError(e, header_added ? 1 : 0));
  }
}

Status WriteCalibration(const std::string& yaml_path, const Calibration& calibration) {
  const Camera& camera = calibration.camera;
  std::string text;
  try {
    cv::FileStorage storage(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    storage << "image_width" << camera.width;
    storage << "image_height" << camera.height;
    storage << "camera_matrix" << cv::Mat(cv::Matx33d(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1));
    // Radtan is written as it always was, without the optional key (SPEC section 1's default).
    if (camera.model != DistortionModel::kRadTan)
      storage << "distortion_model" << DistortionModelName(camera.model);
    storage << "distortion_coefficients" << camera.DistortionCoefficients();
    cv::Mat T;
    cv::eigen2cv(Eigen::Matrix4d(calibration.base_T_camera.Matrix4()), T);
    storage << "T_base_camera" << T;
    if (calibration.odometry_noise_given) {
      storage << "odometry_translation_sigma" << calibration.odometry_noise.translation_sigma;
      storage << "odometry_rotation_sigma" << calibration.odometry_noise.rotation_sigma;
    }
    text = storage.releaseAndGetString();
  } catch (const cv::Exception& e) {
    return Status::Error(yaml_path + ": cannot format calibration (" + OneLine(e.err) + ")");
  }
  return WriteFileAtomically(yaml_path, text);
}

Status ReadSequence(const std::string& directory, Sequence* sequence) {
  std::error_code error;
  if (!fs::exists(directory, error)) return Status::Error(directory + ": sequence directory does not exist");
  if (!fs::is_directory(directory, error)) return Status::Error(directory + ": is not a directory");

  Sequence read;
  read.directory = directory;
  const fs::path root(directory);
  SFM_RETURN_IF_ERROR(ReadCalibration((root / "sequence.yaml").string(), &read.calibration));

  const std::string images_path = (root / "images.txt").string();
  std::vector<int> line_numbers;
  SFM_RETURN_IF_ERROR(ReadImageList(directory, images_path, &read.frames, &line_numbers));

  const std::string odometry_path = (root / "odometry.txt").string();
  std::vector<StampedPose> odometry;
  SFM_RETURN_IF_ERROR(ReadTumTrajectory(odometry_path, &odometry));

  const std::string groundtruth_path = (root / "groundtruth.txt").string();
  std::vector<StampedPose> groundtruth;
  // Present when the name exists at all (a FIFO or a link loop included): the read then names the problem.
  struct stat groundtruth_info;
  read.has_groundtruth = lstat(groundtruth_path.c_str(), &groundtruth_info) == 0;
  if (read.has_groundtruth) SFM_RETURN_IF_ERROR(ReadTumTrajectory(groundtruth_path, &groundtruth));

  SFM_RETURN_IF_ERROR(AssociatePoses(images_path, line_numbers, odometry_path, odometry, &read.frames,
                                     [](Frame* frame, const Pose3& pose) { frame->world_T_base_odometry = pose; }));
  if (read.has_groundtruth) {
    SFM_RETURN_IF_ERROR(AssociatePoses(
        images_path, line_numbers, groundtruth_path, groundtruth, &read.frames,
        [](Frame* frame, const Pose3& pose) { frame->world_T_base_groundtruth = pose; }));
  }
  *sequence = std::move(read);
  return Status::Ok();
}

Status LoadFrameImage(const Sequence& sequence, int frame_index, cv::Mat* grey) {
  CHECK_GE(frame_index, 0);
  CHECK_LT(frame_index, static_cast<int>(sequence.frames.size()));
  const std::string path = (fs::path(sequence.directory) / sequence.frames[frame_index].image_path).string();
  std::string data;
  SFM_RETURN_IF_ERROR(ReadRegularFile(path, "image file", &data));
  const Camera& camera = sequence.calibration.camera;
  auto wrong_size = [&](int width, int height) {
    return Status::Error(path + ": image is " + std::to_string(width) + "x" + std::to_string(height) +
                         ", sequence.yaml says " + std::to_string(camera.width) + "x" +
                         std::to_string(camera.height));
  };
  // The header first: the size is checked before decoding (a small file may declare a huge
  // image), and a truncated JPEG is refused rather than decoded with grey rows.
  const ImageHeader header = ReadImageHeader(data);
  if (!header.problem.empty()) return Status::Error(path + ": " + header.problem);
  if (header.width > 0 && (header.width != camera.width || header.height != camera.height)) {
    return wrong_size(header.width, header.height);
  }
  cv::Mat image;
  try {
    image =
        cv::imdecode(cv::Mat(1, static_cast<int>(data.size()), CV_8UC1, data.data()), cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    return Status::Error(path + ": cannot decode image (" + OneLine(e.err) + ")");
  }
  if (image.empty()) return Status::Error(path + ": cannot decode image");
  if (image.cols != camera.width || image.rows != camera.height) return wrong_size(image.cols, image.rows);
  *grey = image;
  return Status::Ok();
}

}  // namespace sfm

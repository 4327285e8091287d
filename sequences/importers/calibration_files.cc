#include "sequences/importers/calibration_files.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "util/number_text.h"
#include "util/regular_file.h"
#include "util/text_file.h"

namespace sfm {
namespace {

// A 4x4 rigid transform's rotation block must satisfy |R^T R - I| below this (files hold ~9 digits).
constexpr double kRotationTolerance = 1e-5;

// Reads YAML values, failing with "<path>: key '<key>' <problem>".
class YamlReader {
 public:
  YamlReader(const std::string& path, const YAML::Node& root) : path_(path), root_(root) {}

  Status Error(const std::string& key, const std::string& problem) const {
    return Status::Error(path_ + ": key '" + key + "' " + problem);
  }

  // The finite numbers of a flow or block sequence (nested one level for a matrix given as rows).
  Status Numbers(const YAML::Node& node, const std::string& key, std::vector<double>* values) const {
    values->clear();
    if (!node || !node.IsSequence()) return Error(key, "must be a list of numbers");
    for (const YAML::Node& item : node) {
      if (item.IsSequence()) {
        std::vector<double> row;
        SFM_RETURN_IF_ERROR(Numbers(item, key, &row));
        values->insert(values->end(), row.begin(), row.end());
        continue;
      }
      double value = 0;
      if (!item.IsScalar() || !ParseDouble(item.Scalar(), &value) || !std::isfinite(value)) {
        return Error(key, "holds '" + (item.IsScalar() ? item.Scalar() : std::string("a non-number")) +
                              "', not a finite number");
      }
      values->push_back(value);
    }
    return Status::Ok();
  }

  // Exactly `count` numbers under `key` of `node` (a list, or a {rows, cols, data} map).
  Status FixedNumbers(const YAML::Node& node, const std::string& key, const std::vector<size_t>& counts,
                      std::vector<double>* values) const {
    const YAML::Node value = node[key];
    if (!value) return Status::Error(path_ + ": missing key '" + key + "'");
    SFM_RETURN_IF_ERROR(Numbers(value.IsMap() ? value["data"] : value, key, values));
    if (std::find(counts.begin(), counts.end(), values->size()) == counts.end()) {
      std::string expected;
      for (size_t count : counts) expected += (expected.empty() ? "" : " or ") + std::to_string(count);
      return Error(key, "must hold " + expected + " numbers, found " + std::to_string(values->size()));
    }
    return Status::Ok();
  }

  Status Text(const YAML::Node& node, const std::string& key, std::string* text) const {
    const YAML::Node value = node[key];
    if (!value) return Status::Error(path_ + ": missing key '" + key + "'");
    if (!value.IsScalar()) return Error(key, "must be a name");
    *text = value.Scalar();
    return Status::Ok();
  }

  Status PositiveInt(const YAML::Node& node, const std::string& key, int* value) const {
    const YAML::Node item = node[key];
    if (!item) return Status::Error(path_ + ": missing key '" + key + "'");
    double number = 0;
    if (!item.IsScalar() || !ParseDouble(item.Scalar(), &number)) return Error(key, "must be an integer");
    return CheckPositiveInt(key, number, value);
  }

  Status CheckPositiveInt(const std::string& key, double number, int* value) const {
    if (!(number >= 1 && number <= 100000 && number == std::floor(number))) {
      return Error(key, "must be a positive image size in pixels, found " + ShortestNumberText(number));
    }
    *value = static_cast<int>(number);
    return Status::Ok();
  }

  // A rigid 4x4 transform from 16 numbers (row-major).
  Status Rigid(const std::string& key, const std::vector<double>& m, Pose3* pose) const {
    Eigen::Matrix4d T;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) T(r, c) = m[4 * r + c];
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > kRotationTolerance ||
        (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > kRotationTolerance || R.determinant() <= 0) {
      return Error(key, "is not a rigid transform (rotation block not a rotation, or last row not 0 0 0 1)");
    }
    *pose = Pose3::FromMatrix4(T);
    return Status::Ok();
  }

  const std::string& path() const { return path_; }
  const YAML::Node& root() const { return root_; }

 private:
  const std::string& path_;
  const YAML::Node& root_;
};

// The lens model of a file's distortion name and coefficients (1x5 or 1x4 radtan, 1x4 equidistant).
Status SetDistortion(const YamlReader& reader, const std::string& model_key, const std::string& name,
                     const std::vector<double>& coefficients, Camera* camera) {
  const bool radtan = name == "radtan" || name == "plumb_bob" || name == "radial-tangential";
  const bool equidistant = name == "equidistant" || name == "equi";
  if (!radtan && !equidistant) {
    return reader.Error(model_key, "is '" + name +
                                       "', not a supported model (radtan, plumb_bob, radial-tangential or "
                                       "equidistant)");
  }
  camera->model = equidistant ? DistortionModel::kEquidistant : DistortionModel::kRadTan;
  const size_t count = coefficients.size();
  if (equidistant ? count != 4 : (count != 4 && count != 5)) {
    return reader.Error(model_key, "'" + name + "' needs " + (equidistant ? "4" : "4 or 5") +
                                       " distortion coefficients, found " + std::to_string(count));
  }
  camera->distortion = {0, 0, 0, 0, 0};
  std::copy(coefficients.begin(), coefficients.end(), camera->distortion.begin());
  return Status::Ok();
}

Status SetIntrinsics(const YamlReader& reader, const std::string& key, const std::vector<double>& k,
                     Camera* camera) {
  camera->fx = k[0];
  camera->fy = k[1];
  camera->cx = k[2];
  camera->cy = k[3];
  if (!(camera->fx > 0 && camera->fy > 0)) return reader.Error(key, "must have positive focal lengths");
  return Status::Ok();
}

Status CheckPinhole(const YamlReader& reader, const YAML::Node& node) {
  std::string model;
  SFM_RETURN_IF_ERROR(reader.Text(node, "camera_model", &model));
  if (model != "pinhole") return reader.Error("camera_model", "is '" + model + "'; only pinhole is supported");
  return Status::Ok();
}

Status ReadResolution(const YamlReader& reader, const YAML::Node& node, Camera* camera) {
  std::vector<double> size;
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(node, "resolution", {2}, &size));
  SFM_RETURN_IF_ERROR(reader.CheckPositiveInt("resolution", size[0], &camera->width));
  return reader.CheckPositiveInt("resolution", size[1], &camera->height);
}

// Kalibr camchain: cam0's pinhole intrinsics [fu fv pu pv], distortion, resolution, T_cam_imu.
Status ReadKalibr(const YamlReader& reader, const Pose3& base_T_imu, Calibration* calibration) {
  const YAML::Node cam0 = reader.root()["cam0"];
  if (!cam0.IsMap()) return reader.Error("cam0", "must be a map (a Kalibr camchain's first camera)");
  Camera& camera = calibration->camera;
  SFM_RETURN_IF_ERROR(CheckPinhole(reader, cam0));
  std::vector<double> values;
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(cam0, "intrinsics", {4}, &values));
  SFM_RETURN_IF_ERROR(SetIntrinsics(reader, "intrinsics", values, &camera));
  SFM_RETURN_IF_ERROR(ReadResolution(reader, cam0, &camera));
  std::string model;
  SFM_RETURN_IF_ERROR(reader.Text(cam0, "distortion_model", &model));
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(cam0, "distortion_coeffs", {4, 5}, &values));
  SFM_RETURN_IF_ERROR(SetDistortion(reader, "distortion_model", model, values, &camera));
  calibration->base_T_camera = base_T_imu;
  if (cam0["T_cam_imu"]) {
    SFM_RETURN_IF_ERROR(reader.FixedNumbers(cam0, "T_cam_imu", {16}, &values));
    Pose3 cam_T_imu;
    SFM_RETURN_IF_ERROR(reader.Rigid("T_cam_imu", values, &cam_T_imu));
    calibration->base_T_camera = base_T_imu * cam_T_imu.Inverse();
  }
  return Status::Ok();
}

// ROS camera_info (camera_calibration_parsers): image_width/height, camera_matrix, distortion.
Status ReadCameraInfo(const YamlReader& reader, const Pose3& base_T_camera, Calibration* calibration) {
  const YAML::Node& root = reader.root();
  Camera& camera = calibration->camera;
  SFM_RETURN_IF_ERROR(reader.PositiveInt(root, "image_width", &camera.width));
  SFM_RETURN_IF_ERROR(reader.PositiveInt(root, "image_height", &camera.height));
  std::vector<double> K;
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(root, "camera_matrix", {9}, &K));
  if (K[1] != 0 || K[3] != 0 || K[6] != 0 || K[7] != 0 || K[8] != 1) {
    return reader.Error("camera_matrix", "must have the form (fx 0 cx; 0 fy cy; 0 0 1)");
  }
  SFM_RETURN_IF_ERROR(SetIntrinsics(reader, "camera_matrix", {K[0], K[4], K[2], K[5]}, &camera));
  std::string model;
  SFM_RETURN_IF_ERROR(reader.Text(root, "distortion_model", &model));
  std::vector<double> coefficients;
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(root, "distortion_coefficients", {4, 5}, &coefficients));
  SFM_RETURN_IF_ERROR(SetDistortion(reader, "distortion_model", model, coefficients, &camera));
  calibration->base_T_camera = base_T_camera;
  return Status::Ok();
}

// EuRoC / ASL sensor.yaml of a camera: T_BS, resolution, camera_model, intrinsics, distortion.
Status ReadEurocSensor(const YamlReader& reader, const Pose3& base_T_body, Calibration* calibration) {
  const YAML::Node& root = reader.root();
  Camera& camera = calibration->camera;
  SFM_RETURN_IF_ERROR(CheckPinhole(reader, root));
  std::vector<double> values;
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(root, "intrinsics", {4}, &values));
  SFM_RETURN_IF_ERROR(SetIntrinsics(reader, "intrinsics", values, &camera));
  SFM_RETURN_IF_ERROR(ReadResolution(reader, root, &camera));
  std::string model;
  SFM_RETURN_IF_ERROR(reader.Text(root, "distortion_model", &model));
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(root, "distortion_coefficients", {4, 5}, &values));
  SFM_RETURN_IF_ERROR(SetDistortion(reader, "distortion_model", model, values, &camera));
  SFM_RETURN_IF_ERROR(reader.FixedNumbers(root, "T_BS", {16}, &values));
  Pose3 body_T_sensor;
  SFM_RETURN_IF_ERROR(reader.Rigid("T_BS", values, &body_T_sensor));
  calibration->base_T_camera = base_T_body * body_T_sensor;
  return Status::Ok();
}

}  // namespace

const char* CalibrationFileKindName(CalibrationFileKind kind) {
  switch (kind) {
    case CalibrationFileKind::kKalibr:
      return "Kalibr camchain";
    case CalibrationFileKind::kCameraInfo:
      return "ROS camera_info";
    case CalibrationFileKind::kEurocSensor:
      return "EuRoC sensor.yaml";
    default:
      return "OpenCV YAML";
  }
}

Status ReadCalibrationFile(const std::string& path, const Pose3& base_T_reference, Calibration* calibration,
                           CalibrationFileKind* kind) {
  CalibrationFileKind ignored;
  if (kind == nullptr) kind = &ignored;
  std::string text;
  SFM_RETURN_IF_ERROR(ReadRegularFile(path, "calibration file", &text, size_t(1) << 24));
  if (text.find("!!opencv-matrix") != std::string::npos) {
    *kind = CalibrationFileKind::kOpenCv;
    return ReadCalibration(path, calibration);
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return Status::Error(path + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML (" + e.msg + ")");
  }
  if (!root.IsMap()) return Status::Error(path + ": not a YAML map of calibration keys");
  *calibration = Calibration();
  const YamlReader reader(path, root);
  try {
    if (root["cam0"]) {
      *kind = CalibrationFileKind::kKalibr;
      return ReadKalibr(reader, base_T_reference, calibration);
    }
    if (root["T_BS"]) {
      *kind = CalibrationFileKind::kEurocSensor;
      return ReadEurocSensor(reader, base_T_reference, calibration);
    }
    if (root["camera_matrix"]) {
      *kind = CalibrationFileKind::kCameraInfo;
      return ReadCameraInfo(reader, base_T_reference, calibration);
    }
  } catch (const YAML::Exception& e) {
    return Status::Error(path + ":" + std::to_string(e.mark.line + 1) + ": unexpected YAML structure (" + e.msg +
                         ")");
  }
  return Status::Error(path +
                       ": not a known calibration layout (no cam0: Kalibr camchain; no camera_matrix: ROS "
                       "camera_info; no T_BS: EuRoC sensor.yaml; no !!opencv-matrix: OpenCV YAML)");
}

Status ParsePoseText(const std::string& text, const std::string& what, Pose3* pose) {
  const std::vector<std::string> words = SplitWords(text);
  if (words.empty()) {
    *pose = Pose3();
    return Status::Ok();
  }
  double v[7];
  bool ok = words.size() == 7;
  for (size_t i = 0; ok && i < 7; ++i) ok = ParseDouble(words[i], &v[i]) && std::isfinite(v[i]);
  if (!ok) return Status::Error(what + ": expected 'tx ty tz qx qy qz qw', found '" + text + "'");
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (std::abs(q.norm() - 1) > 1e-3) {
    return Status::Error(what + ": the quaternion's norm is " + ShortestNumberText(q.norm()) + ", not 1");
  }
  *pose = Pose3(q.normalized(), Eigen::Vector3d(v[0], v[1], v[2]));
  return Status::Ok();
}

}  // namespace sfm

#include "sequences/importers/strecha_importer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <Eigen/SVD>
#include <glog/logging.h>

#include "util/number_text.h"
#include "sequences/importers/input_files.h"

namespace sfm {
namespace {
namespace fs = std::filesystem;

constexpr size_t kNumbersPerCamera = 26;
// The files give R to 6 significant digits: |R^T R - I| is ~1e-6 for a true rotation.
constexpr double kRotationTolerance = 1e-4;
constexpr char kCameraSuffix[] = ".camera";

// The rotation nearest to R (Frobenius norm), by SVD.
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& R) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

bool SameCamera(const Camera& a, const Camera& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy;
}

}  // namespace

Status ReadStrechaCamera(const std::string& path, StrechaCamera* camera) {
  std::vector<double> n;
  SFM_RETURN_IF_ERROR(ReadNumbers(path, &n));
  if (n.size() != kNumbersPerCamera) {
    return Status::Error(path + ": expected 26 numbers (K, distortion, R, C, width height), found " +
                         std::to_string(n.size()));
  }
  if (n[1] != 0 || n[3] != 0 || n[6] != 0 || n[7] != 0 || n[8] != 1) {
    return Status::Error(path + ": K must have the form (fx 0 cx; 0 fy cy; 0 0 1)");
  }
  if (!(n[0] > 0 && n[4] > 0)) return Status::Error(path + ": K's focal lengths must be positive");
  if (n[9] != 0 || n[10] != 0 || n[11] != 0) {
    return Status::Error(path + ": nonzero distortion; only undistorted Strecha images are supported");
  }
  Eigen::Matrix3d R;
  R << n[12], n[13], n[14], n[15], n[16], n[17], n[18], n[19], n[20];
  const double orthogonality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (orthogonality_error > kRotationTolerance || R.determinant() <= 0) {
    return Status::Error(path + ": R is not a rotation (|R^T R - I| = " + ShortestNumberText(orthogonality_error) +
                         ", det R = " + ShortestNumberText(R.determinant()) + ")");
  }
  const double width = n[24], height = n[25];
  if (!(width >= 1 && height >= 1 && width == std::floor(width) && height == std::floor(height) && width < 1e6 &&
        height < 1e6)) {
    return Status::Error(path + ": image size must be positive whole pixels, found " + ShortestNumberText(width) + " x " +
                         ShortestNumberText(height));
  }
  camera->camera = Camera();
  camera->camera.width = static_cast<int>(width);
  camera->camera.height = static_cast<int>(height);
  camera->camera.fx = n[0];
  camera->camera.cx = n[2];
  camera->camera.fy = n[4];
  camera->camera.cy = n[5];
  // x ~ K R^T (X - C): camera_T_world = (R^T, -R^T C), so world_T_camera = (R, C).
  camera->world_T_camera = Pose3(NearestRotation(R), Eigen::Vector3d(n[21], n[22], n[23]));
  return Status::Ok();
}

Status ReadStrechaSequence(const std::string& input_dir, ImportedSequence* sequence) {
  const fs::path dir(input_dir), cameras_dir = fs::path(input_dir) / "gt_dense_cameras";
  std::error_code error;
  if (!fs::is_directory(dir, error)) return Status::Error(input_dir + ": input directory does not exist");
  if (!fs::is_directory(cameras_dir, error)) {
    return Status::Error(cameras_dir.string() + ": camera folder does not exist (expected a Strecha folder)");
  }
  std::vector<std::string> camera_files;
  for (const fs::directory_entry& entry : fs::directory_iterator(cameras_dir, error)) {
    const std::string file = entry.path().filename().string();
    const size_t suffix = sizeof(kCameraSuffix) - 1;
    if (file.size() > suffix && file.compare(file.size() - suffix, suffix, kCameraSuffix) == 0) {
      camera_files.push_back(file);
    }
  }
  if (error) return Status::Error(cameras_dir.string() + ": cannot list (" + error.message() + ")");
  if (camera_files.empty()) return Status::Error(cameras_dir.string() + ": no camera files (<image>.camera)");
  std::sort(camera_files.begin(), camera_files.end());

  ImportedSequence imported;
  for (size_t i = 0; i < camera_files.size(); ++i) {
    const std::string camera_path = (cameras_dir / camera_files[i]).string();
    const std::string image_name = camera_files[i].substr(0, camera_files[i].size() - (sizeof(kCameraSuffix) - 1));
    const std::string image_path = (dir / "images" / image_name).string();
    if (!fs::is_regular_file(image_path, error)) {
      return Status::Error(image_path + ": image file for " + camera_files[i] + " does not exist");
    }
    StrechaCamera camera;
    SFM_RETURN_IF_ERROR(ReadStrechaCamera(camera_path, &camera));
    if (i == 0) {
      imported.camera = camera.camera;
    } else if (!SameCamera(camera.camera, imported.camera)) {
      return Status::Error(camera_path + ": K or image size differs from " + camera_files[0] +
                           "'s; a sequence has one camera");
    }
    imported.frames.push_back(
        {static_cast<double>(i) * kFrameInterval, image_path, camera.world_T_camera, std::nullopt});
  }
  imported.notes.push_back("format: Strecha, " + input_dir + ", " + std::to_string(imported.frames.size()) +
                           " frames " + camera_files.front() + " .. " + camera_files.back());
  imported.notes.push_back("K and poses: the camera files' (x ~ K R^T (X - C), world_T_camera = (R, C)), metres");
  imported.notes.push_back("timestamps: 0.1 s per frame (the data set has none)");
  LOG(INFO) << "Strecha: " << imported.frames.size() << " cameras, K fx " << imported.camera.fx << " fy "
            << imported.camera.fy << " cx " << imported.camera.cx << " cy " << imported.camera.cy << " for "
            << imported.camera.width << "x" << imported.camera.height;
  *sequence = std::move(imported);
  return Status::Ok();
}

}  // namespace sfm

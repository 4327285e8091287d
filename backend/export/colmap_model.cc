#include "backend/export/colmap_model.h"

#include <glog/logging.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include "util/atomic_file.h"
#include "util/number_text.h"

namespace sfm {
namespace {

// COLMAP's pixel origin is the top-left corner of the image, OpenCV's the centre of the top-left pixel.
constexpr double kColmapPixelShift = 0.5;
// Junctions carry no colour; mid grey shows on both light and dark backgrounds.
constexpr const char* kPointColour = "128 128 128";
// COLMAP's Point3D error value for "not computed".
constexpr double kUnknownError = -1;

std::string Numbers(std::initializer_list<double> values) {
  std::string text;
  for (const double value : values) {
    if (!text.empty()) text += ' ';
    text += ShortestNumberText(value);
  }
  return text;
}

std::string FilePath(const std::string& directory, const char* name) {
  return (std::filesystem::path(directory) / name).string();
}

double Mean(size_t total, size_t count) {
  return count == 0 ? 0.0 : static_cast<double>(total) / static_cast<double>(count);
}

// The POINT3D_ID of model.points[i].
long PointId(const ColmapModel& model, size_t i) {
  return model.points[i].id > 0 ? model.points[i].id : static_cast<long>(i) + 1;
}

// A 2D point of images.txt: where it is and which 3D point it observes.
struct ImagePoint {
  Eigen::Vector2d pixel;  // OpenCV convention
  int point_index = 0;
};

// Checks every number and name before any file is written, so a bad model leaves no file behind.
Status Validate(const std::string& directory, const ColmapModel& model) {
  const std::string images_file = FilePath(directory, "images.txt");
  const std::string points_file = FilePath(directory, "points3D.txt");
  const Camera& camera = model.camera;
  if (!Eigen::Vector4d(camera.fx, camera.fy, camera.cx, camera.cy).allFinite()) {
    return Status::Error(FilePath(directory, "cameras.txt") + ": camera intrinsics are not finite");
  }
  for (size_t i = 0; i < model.images.size(); ++i) {
    const ColmapImage& image = model.images[i];
    const std::string which = images_file + ": image " + std::to_string(i) + " ('" + image.name + "')";
    if (image.name.empty())
      return Status::Error(images_file + ": image " + std::to_string(i) + " has no name");
    if (!IsColmapImageName(image.name)) {
      return Status::Error(which + ": the name holds whitespace, which COLMAP cannot read back");
    }
    if (!image.world_T_camera.rotation.coeffs().allFinite() ||
        !image.world_T_camera.translation.allFinite()) {
      return Status::Error(which + ": the pose is not finite");
    }
  }
  std::set<long> ids;
  for (size_t i = 0; i < model.points.size(); ++i) {
    const ColmapPoint& point = model.points[i];
    if (!ids.insert(PointId(model, i)).second) {
      return Status::Error(points_file + ": point " + std::to_string(i) + " repeats the POINT3D_ID " +
                           std::to_string(PointId(model, i)));
    }
    if (!point.position.allFinite()) {
      return Status::Error(points_file + ": point " + std::to_string(i) + " has a non-finite position");
    }
    for (const ColmapObservation& observation : point.track) {
      CHECK(observation.image_index >= 0 && observation.image_index < static_cast<int>(model.images.size()))
          << "point " << i << " observed in image " << observation.image_index << " of "
          << model.images.size();
      if (!observation.pixel.allFinite()) {
        return Status::Error(points_file + ": point " + std::to_string(i) + " has a non-finite observation");
      }
    }
  }
  return Status::Ok();
}

// A fisheye's undistorted image cannot hold its view (at 90 degrees off axis it is infinite), so
// an equidistant camera is written as COLMAP's OPENCV_FISHEYE (the same cv::fisheye model) and its
// observations in the stored image's pixels; the radial-tangential model stays a PINHOLE camera of
// the undistorted images.
bool WritesStoredPixels(const Camera& camera) { return camera.model == DistortionModel::kEquidistant; }

// An observation (undistorted pixel, OpenCV convention) as the model's camera sees it, OpenCV convention.
Eigen::Vector2d ModelPixel(const Camera& camera, const Eigen::Vector2d& undistorted) {
  return WritesStoredPixels(camera) ? camera.DistortPixel(undistorted) : undistorted;
}

std::string CamerasText(const Camera& camera) {
  std::string line = "1 PINHOLE ";
  std::string coefficients;
  if (WritesStoredPixels(camera)) {
    line = "1 OPENCV_FISHEYE ";
    const auto& d = camera.distortion;
    coefficients = " " + Numbers({d[0], d[1], d[2], d[3]});
  }
  return "# Camera list with one line of data per camera:\n"
         "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
         "# Number of cameras: 1\n" +
         line + std::to_string(camera.width) + " " + std::to_string(camera.height) + " " +
         Numbers({camera.fx, camera.fy, camera.cx + kColmapPixelShift, camera.cy + kColmapPixelShift}) +
         coefficients + "\n";
}

std::string ImagesText(const ColmapModel& model, const std::vector<std::vector<ImagePoint>>& image_points,
                       size_t observations) {
  std::string text =
      "# Image list with two lines of data per image:\n"
      "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
      "# Number of images: " +
      std::to_string(model.images.size()) +
      ", mean observations per image: " + ShortestNumberText(Mean(observations, model.images.size())) + "\n";
  for (size_t k = 0; k < model.images.size(); ++k) {
    const Pose3 camera_T_world = model.images[k].world_T_camera.Inverse();
    Eigen::Quaterniond q = camera_T_world.rotation.normalized();
    if (q.w() < 0) q.coeffs() = -q.coeffs();  // q and -q are the same rotation; write one of them
    const Eigen::Vector3d& t = camera_T_world.translation;
    text += std::to_string(k + 1) + " " + Numbers({q.w(), q.x(), q.y(), q.z(), t.x(), t.y(), t.z()}) + " 1 " +
            model.images[k].name + "\n";
    std::string points_line;
    for (const ImagePoint& image_point : image_points[k]) {
      if (!points_line.empty()) points_line += ' ';
      points_line +=
          Numbers({image_point.pixel.x() + kColmapPixelShift, image_point.pixel.y() + kColmapPixelShift}) +
          " " + std::to_string(PointId(model, image_point.point_index));
    }
    text += points_line + "\n";
  }
  return text;
}

// Mean distance in pixels between the observations and the projections of the point (K only for
// the undistorted observations of a PINHOLE camera, the lens too for OPENCV_FISHEYE), or
// kUnknownError when a camera does not see it in front.
double ReprojectionError(const ColmapModel& model, const ColmapPoint& point) {
  if (point.track.empty()) return kUnknownError;
  double sum = 0;
  for (const ColmapObservation& observation : point.track) {
    const Eigen::Vector3d point_camera =
        model.images[observation.image_index].world_T_camera.Inverse() * point.position;
    if (!(point_camera.z() > 0)) return kUnknownError;
    const Eigen::Vector2d projected = WritesStoredPixels(model.camera)
                                          ? model.camera.Project(point_camera)
                                          : model.camera.ProjectUndistorted(point_camera);
    sum += (projected - ModelPixel(model.camera, observation.pixel)).norm();
  }
  return sum / static_cast<double>(point.track.size());
}

std::string Points3DText(const ColmapModel& model, const std::vector<std::vector<int>>& point2d_indices,
                         size_t observations) {
  std::string text =
      "# 3D point list with one line of data per point:\n"
      "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      "# Number of points: " +
      std::to_string(model.points.size()) +
      ", mean track length: " + ShortestNumberText(Mean(observations, model.points.size())) + "\n";
  for (size_t i = 0; i < model.points.size(); ++i) {
    const ColmapPoint& point = model.points[i];
    text += std::to_string(PointId(model, i)) + " " +
            Numbers({point.position.x(), point.position.y(), point.position.z()}) + " " + kPointColour + " " +
            ShortestNumberText(ReprojectionError(model, point));
    for (size_t j = 0; j < point.track.size(); ++j) {
      text +=
          " " + std::to_string(point.track[j].image_index + 1) + " " + std::to_string(point2d_indices[i][j]);
    }
    text += "\n";
  }
  return text;
}

}  // namespace

bool IsColmapImageName(const std::string& name) {
  return !name.empty() && std::none_of(name.begin(), name.end(),
                                       [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

Status WriteColmapModel(const std::string& directory, const ColmapModel& model) {
  SFM_RETURN_IF_ERROR(Validate(directory, model));

  // Lay out each image's 2D points (points in order, then track order) and remember, for every
  // track element, its position in that layout: the POINT2D_IDX of points3D.txt.
  std::vector<std::vector<ImagePoint>> image_points(model.images.size());
  std::vector<std::vector<int>> point2d_indices(model.points.size());
  size_t observations = 0;
  for (size_t i = 0; i < model.points.size(); ++i) {
    for (const ColmapObservation& observation : model.points[i].track) {
      std::vector<ImagePoint>& in_image = image_points[observation.image_index];
      point2d_indices[i].push_back(static_cast<int>(in_image.size()));
      in_image.push_back({ModelPixel(model.camera, observation.pixel), static_cast<int>(i)});
      ++observations;
    }
  }

  SFM_RETURN_IF_ERROR(EnsureWritableDirectory(directory));
  SFM_RETURN_IF_ERROR(WriteFileAtomically(FilePath(directory, "cameras.txt"), CamerasText(model.camera)));
  SFM_RETURN_IF_ERROR(
      WriteFileAtomically(FilePath(directory, "images.txt"), ImagesText(model, image_points, observations)));
  return WriteFileAtomically(FilePath(directory, "points3D.txt"),
                             Points3DText(model, point2d_indices, observations));
}

}  // namespace sfm

// The colmap/ output (SPEC section 3): a COLMAP sparse model in COLMAP's text format
// (cameras.txt, images.txt, points3D.txt; https://colmap.github.io/format.html), so the
// reconstruction opens in COLMAP's GUI and tools (model_analyzer, model_converter).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/camera.h"
#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct ColmapImage {
  std::string name;      // image path relative to the sequence directory, e.g. "images/000012.png"
  Pose3 world_T_camera;  // the camera's pose in the world
};

struct ColmapObservation {
  int image_index = 0;                              // 0-based index into ColmapModel::images
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted pixel, OpenCV convention
};

struct ColmapPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world frame, metres
  std::vector<ColmapObservation> track;                // the images that see the point
  long id = 0;  // POINT3D_ID when > 0 (unique over the model), else the point's 0-based index + 1
};

// What the export needs: one camera shared by all images, the posed images, the 3D points.
struct ColmapModel {
  Camera camera;  // radtan: K and the size (PINHOLE, undistorted images); equidistant: OPENCV_FISHEYE
  std::vector<ColmapImage> images;
  std::vector<ColmapPoint> points;
};

// Writes `directory`/cameras.txt, images.txt and points3D.txt, each atomically, creating the
// directory. Conversions to COLMAP's conventions:
// - one camera, CAMERA_ID 1: PINHOLE (K) with the undistorted observations, or for an equidistant
//   lens OPENCV_FISHEYE (K, k1..k4) with the observations distorted into the stored images' pixels;
//   IMAGE_ID is the 0-based index + 1, POINT3D_ID the point's id (ColmapPoint::id), or its 0-based
//   index + 1 when it has none;
// - poses are stored as camera_T_world (COLMAP's cam_from_world), quaternion QW QX QY QZ with
//   QW >= 0, so a camera at world position c with identity rotation has TX TY TZ = -c;
// - COLMAP puts the centre of the top-left pixel at (0.5, 0.5), OpenCV at (0, 0): cx, cy and every
//   observation are shifted by +0.5 pixel;
// - the observations of image k are listed in images.txt in the order of the points, then of each
//   point's track, and POINT2D_IDX in points3D.txt is the 0-based position in that list;
// - colour is a fixed grey (junctions carry none); ERROR is the mean reprojection error in pixels
//   with the camera model, or -1 (COLMAP's "unknown") when the point is not in front of every observing
//   camera.
// Observation image indices must be valid (CHECKed). Fails, naming the file, on a POINT3D_ID used
// twice, an image name that is empty or holds whitespace (COLMAP splits lines on spaces), a non-finite
// pose, point or pixel, or when the directory or a file cannot be written.
Status WriteColmapModel(const std::string& directory, const ColmapModel& model);

// Whether COLMAP's images.txt can hold `name` as an image's NAME: not empty, no white space.
bool IsColmapImageName(const std::string& name);

}  // namespace sfm

// Camera: pinhole intrinsics with OpenCV's distortion model (k1 k2 p1 p2 k3).
//
// Pixels follow OpenCV: x right, y down, origin at the centre of the top-left pixel. The camera
// frame is x right, y down, z forward. "Normalised" coordinates are (X/Z, Y/Z) before distortion.
#pragma once

#include <array>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace sfm {

struct Camera {
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;            // pixels
  std::array<double, 5> distortion{0, 0, 0, 0, 0};  // k1 k2 p1 p2 k3 (OpenCV order)

  Eigen::Matrix3d K() const;
  bool HasDistortion() const;

  // Normalised point -> distorted normalised point (OpenCV's model).
  Eigen::Vector2d Distort(const Eigen::Vector2d& normalised) const;
  // Inverse of Distort, by Newton iteration (accurate to < 1e-10 for the model's usual range).
  Eigen::Vector2d Undistort(const Eigen::Vector2d& distorted) const;

  // Point in the camera frame -> pixel of the stored (distorted) image. Z must be > 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_camera) const;
  // Point in the camera frame -> pixel of the undistorted image (K only).
  Eigen::Vector2d ProjectUndistorted(const Eigen::Vector3d& point_camera) const;

  // Pixel of the stored image -> pixel of the undistorted image (same K), and back.
  Eigen::Vector2d UndistortPixel(const Eigen::Vector2d& pixel) const;
  Eigen::Vector2d DistortPixel(const Eigen::Vector2d& undistorted_pixel) const;

  // The whole image resampled to the undistorted geometry (same size and K, bilinear); a copy when
  // there is no distortion. The image must be width x height (CHECKed: LoadFrameImage ensures it).
  // For a sequence of frames use ImageUndistorter (image_undistorter.h), which builds its maps once.
  cv::Mat UndistortImage(const cv::Mat& image) const;
};

}  // namespace sfm

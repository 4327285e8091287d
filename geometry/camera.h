// Camera: pinhole intrinsics with one of OpenCV's two lens models: the radial-tangential model
// (k1 k2 p1 p2 k3, ROS plumb_bob, Kalibr radtan) or the equidistant fisheye model of cv::fisheye
// (Kannala-Brandt k1 k2 k3 k4, Kalibr equi; SPEC section 1 `distortion_model`).
//
// Pixels follow OpenCV: x right, y down, origin at the centre of the top-left pixel. The camera
// frame is x right, y down, z forward. "Normalised" coordinates are (X/Z, Y/Z) before distortion.
#pragma once

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <string>

namespace sfm {

// sequence.yaml's `distortion_model` (SPEC section 1).
enum class DistortionModel {
  kRadTan,       // OpenCV's standard model: x (1 + k1 r^2 + k2 r^4 + k3 r^6) plus tangential p1, p2
  kEquidistant,  // cv::fisheye: distorted radius theta (1 + k1 theta^2 + .. + k4 theta^8), theta = atan(r)
};

// "radtan" or "equidistant" (the names of sequence.yaml); false for any other name.
bool ParseDistortionModel(const std::string& name, DistortionModel* model);
const char* DistortionModelName(DistortionModel model);

struct Camera {
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  DistortionModel model = DistortionModel::kRadTan;
  // kRadTan: k1 k2 p1 p2 k3 (OpenCV order). kEquidistant: k1 k2 k3 k4 (cv::fisheye order), the
  // fifth entry 0.
  std::array<double, 5> distortion{0, 0, 0, 0, 0};

  Eigen::Matrix3d K() const;
  // Radtan: a coefficient is not zero. Equidistant: always (with zero coefficients it is still the
  // f-theta projection, not the pinhole).
  bool HasDistortion() const;
  // The coefficients as OpenCV's functions take them: 1x5 (radtan) or 1x4 (equidistant), CV_64F.
  cv::Mat DistortionCoefficients() const;

  // Normalised point -> distorted normalised point (radtan: OpenCV's model; equidistant:
  // cv::fisheye::distortPoints).
  Eigen::Vector2d Distort(const Eigen::Vector2d& normalised) const;
  // Inverse of Distort (radtan: Newton iteration, accurate to < 1e-10 for the model's usual range;
  // equidistant: cv::fisheye::undistortPoints to 1e-14 rad in theta). Beyond where the lens model
  // is one-to-one, the equidistant inverse is cv::fisheye's (-1e6, -1e6).
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

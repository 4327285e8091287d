// ImageUndistorter: resamples images of a distorted camera to its undistorted geometry (same K;
// the same size, or a canvas holding the stored image's whole field of view). The remap tables
// are built once per camera, not once per frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "geometry/camera.h"

namespace sfm {

// How the undistorted image is resampled from the stored one (cv::remap's interpolation).
enum class UndistortInterpolation { kLinear, kCubic, kLanczos4 };

// The resampling of frames before detection (PipelineOptions, the apps' --undistort_interpolation).
// Bilinear blurs every edge (keeps about 0.89 of a step's peak gradient, cubic 0.99) and merges
// close corners: cubic finds 0.7-1.1 points more junctions on generated sequences with a lens. It
// stays linear by default: end to end its mean effect over noise draws is nil, but on the project's
// fixed draws it turns the VGG back-end ATE ratio 0.980 -> 1.018 (a readout of the last 0.1 % of
// scale) and held-out turns-dist's wireframe 0.908 -> 0.888 (-0.006 +- 0.004 over 19 noise draws):
// docs/decisions.md.
constexpr UndistortInterpolation kDetectionInterpolation = UndistortInterpolation::kLinear;

// "linear", "cubic" or "lanczos4"; false for any other name.
bool ParseUndistortInterpolation(const std::string& name, UndistortInterpolation* interpolation);
// The name ParseUndistortInterpolation reads.
const char* UndistortInterpolationName(UndistortInterpolation interpolation);

// What the undistorted image covers (PipelineOptions::undistort_full_view, the apps'
// --undistort_full_view).
enum class UndistortView {
  // The undistorted image has the stored image's size and K. Under barrel distortion (k1 < 0) it
  // drops what the stored image sees near its sides (about 50 px per side at k1 = -0.25, 640 px).
  kSameSize,
  // A canvas with K's focal lengths whose principal point is shifted by (left, top) margins, just
  // large enough for the undistorted border of the stored image: the whole field of view. Canvas
  // pixels whose source lies outside the stored image repeat the stored image's nearest border
  // pixel (no step edge there; the segments found there are cut off by ClipSegmentsToStoredView).
  kFullView,
};

// The view of detection (PipelineOptions::undistort_full_view, the apps' --undistort_full_view).
// Full view by default: over 33 lens sequence x noise-draw pairs (barrel k1 = -0.12 .. -0.35 and
// pincushion) it finds 8 % more junctions per frame, turns the rotation ratio 0.146 -> 0.129
// (26 of 33 better) and the wireframe share 0.949 -> 0.958 (26 of 33), lifts the one goal miss
// (0.883 -> 0.900) and leaves the ATE ratio as it was on average (0.086 -> 0.086), though worse on
// corridor turns (0.068 -> 0.085) and on held-out room-dist's draws (0.107 -> 0.132). About
// 1.3 ms per 640 x 480 frame more (docs/decisions.md).
constexpr UndistortView kDetectionView = UndistortView::kFullView;

// A pinhole view of part of a wide lens's field of view: the camera rotated by view_R_camera, with
// its own intrinsics. Straight 3D lines are straight in it, as in K's image, and near its axis one
// sub-view pixel is a fixed share of a stored pixel (kSubViewZoom), where K's canvas stretches the
// periphery of a wide lens many times.
struct PerspectiveSubView {
  Eigen::Matrix3d view_R_camera = Eigen::Matrix3d::Identity();
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels of the sub-view
  cv::Size size;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // its optical axis in the camera frame
  // K camera_R_view K_view^-1: sub-view pixels to K's undistorted pixels.
  Eigen::Matrix3d undistorted_H_view = Eigen::Matrix3d::Identity();

  // Pixel of the sub-view -> unit ray in the camera frame.
  Eigen::Vector3d Ray(const Eigen::Vector2d& pixel) const;
  // Pixel of the sub-view -> pixel of K's undistorted image: a homography (undistorted_H_view), so
  // a segment maps to a segment. The ray must be in front of the camera (z > 0).
  Eigen::Vector2d ToUndistorted(const Eigen::Vector2d& pixel) const;
};

// The sub-views an equidistant lens is detected on (ImageUndistorter with kFullView): a grid of
// pinhole views whose axes are at most about kSubViewCellDeg apart in yaw and pitch (a 150 degree
// lens: 3 x 3), each with kSubViewZoom times the lens's focal length and just large enough for the
// rays closest to its axis (its cell, sampled every 2 stored pixels) plus `margin` px. Empty when
// the camera is not equidistant.
constexpr double kSubViewCellDeg = 50;
// The sub-views' focal length over the lens's (its angular resolution on the axis). At 1.0 the
// junction locations are a stored pixel coarse: fisheye rooms' recall within 3 undistorted px fell
// below the canvas's (85.7 % against 88.2 %); at 1.5 it is 89.5 %, and 92.1 % in stored pixels
// (1.0: 89.4 %). The pinhole of the same rooms has 1.47 times the fisheye's focal length.
constexpr double kSubViewZoom = 1.5;
std::vector<PerspectiveSubView> EquidistantSubViews(const Camera& camera, int margin);

class ImageUndistorter {
 public:
  explicit ImageUndistorter(const Camera& camera,
                            UndistortInterpolation interpolation = UndistortInterpolation::kLinear,
                            UndistortView view = UndistortView::kSameSize);

  // The undistorted image (resampled with the constructor's interpolation); a shallow copy of the
  // input when the camera has no distortion. kSameSize: black outside the field of view; kFullView:
  // the canvas (CanvasOffset). CHECKs that the image is of the camera's size.
  cv::Mat Apply(const cv::Mat& image) const;

  // Canvas pixel = K's pixel + CanvasOffset(): (left, top) margins of the full-view canvas; zero for
  // kSameSize and for cameras without distortion.
  Eigen::Vector2d CanvasOffset() const { return offset_; }
  cv::Size CanvasSize() const { return canvas_size_; }
  // True for kFullView on a camera with distortion (the canvas may still be the image's size: a
  // pincushion lens sees less than K's image).
  bool FullView() const { return full_view_; }
  const Camera& camera() const { return camera_; }

  // kFullView on an equidistant lens: the perspective sub-views detection runs on instead of one
  // canvas (on the canvas, a 150 degree lens's periphery is stretched up to 1/cos^2(75 deg) = 15
  // times along the radius, so the detector's pixel thresholds meant a fraction of a stored pixel
  // there). Empty otherwise.
  const std::vector<PerspectiveSubView>& SubViews() const { return sub_views_; }
  // The index of the sub-view whose axis is closest to `ray` (camera frame): the one whose
  // junctions are kept there.
  int SubViewOf(const Eigen::Vector3d& ray) const;
  // Sub-view k of the stored image (the constructor's interpolation; beyond the stored image its
  // nearest border pixel, as on the canvas).
  cv::Mat ApplySubView(int k, const cv::Mat& image) const;
  // True when pixel `pixel` of sub-view k is seen by the stored image at least `margin` px inside
  // its border (SeenByStoredImage's test, through the sub-view's remap tables).
  bool SubViewSees(int k, const Eigen::Vector2d& pixel, double margin) const;

 private:
  Camera camera_;
  int interpolation_;      // cv::INTER_*
  int border_mode_;        // cv::BORDER_*
  bool full_view_ = false;
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();
  cv::Size canvas_size_;
  cv::Mat map_x_, map_y_;  // empty when there is no distortion
  std::vector<PerspectiveSubView> sub_views_;
  std::vector<cv::Mat> sub_map_x_, sub_map_y_;
};

// The full-view canvas of `camera`: (left, top) margins and size, with `pad` px beyond the
// bounding box of the stored image's undistorted border (sampled every pixel along the four
// sides). Never smaller than the stored image (left, top >= 0).
void FullViewCanvas(const Camera& camera, int pad, Eigen::Vector2d* offset, cv::Size* size);

// The normalised radius at which the radial distortion r (1 + k1 r^2 + k2 r^4 + k3 r^6) stops
// growing (its derivative reaches 0), +infinity when it grows up to r = 10: beyond it the model
// folds back and an undistorted pixel is not one stored pixel. Equidistant: tan(theta) at the
// angle where theta (1 + k1 theta^2 + .. + k4 theta^8) stops growing, +infinity when it grows up to
// a right angle.
double RadialFoldRadius(const Camera& camera);

// True when the full-view canvas (offset, size from FullViewCanvas) lies inside the radial fold
// radius and every border pixel of the stored image survives undistortion and distortion back to
// 0.01 px. Otherwise ImageUndistorter falls back to the same-size view (with a warning).
bool FullViewIsWellDefined(const Camera& camera, const Eigen::Vector2d& offset, const cv::Size& size);

// The canvas ImageUndistorter detects on for `view`, with `pad` px beyond the field of view: the
// full-view canvas (FullViewCanvas) when view is kFullView, the camera has distortion and
// FullViewIsWellDefined (returns true); otherwise the image itself, offset zero (returns false).
bool DetectionCanvas(const Camera& camera, UndistortView view, int pad, Eigen::Vector2d* offset,
                     cv::Size* size);

// True when undistorted pixel `p` (K's frame) is seen by the stored image at least `margin` px
// inside its border (always inside without distortion: then only the image rectangle counts).
bool SeenByStoredImage(const Camera& camera, const Eigen::Vector2d& p, double margin);

}  // namespace sfm

#include "geometry/image_undistorter.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace sfm {

bool ParseUndistortInterpolation(const std::string& name, UndistortInterpolation* interpolation) {
  if (name == "linear")
    *interpolation = UndistortInterpolation::kLinear;
  else if (name == "cubic")
    *interpolation = UndistortInterpolation::kCubic;
  else if (name == "lanczos4")
    *interpolation = UndistortInterpolation::kLanczos4;
  else
    return false;
  return true;
}

const char* UndistortInterpolationName(UndistortInterpolation interpolation) {
  switch (interpolation) {
    case UndistortInterpolation::kCubic:
      return "cubic";
    case UndistortInterpolation::kLanczos4:
      return "lanczos4";
    default:
      return "linear";
  }
}

void FullViewCanvas(const Camera& camera, int pad, Eigen::Vector2d* offset, cv::Size* size) {
  double min_x = 0, min_y = 0, max_x = camera.width - 1, max_y = camera.height - 1;
  auto add = [&](double x, double y) {
    const Eigen::Vector2d u = camera.UndistortPixel(Eigen::Vector2d(x, y));
    min_x = std::min(min_x, u.x()), max_x = std::max(max_x, u.x());
    min_y = std::min(min_y, u.y()), max_y = std::max(max_y, u.y());
  };
  for (int x = 0; x < camera.width; ++x) add(x, 0), add(x, camera.height - 1);
  for (int y = 0; y < camera.height; ++y) add(0, y), add(camera.width - 1, y);
  const int left = static_cast<int>(std::ceil(-min_x)) + pad * (min_x < 0);
  const int top = static_cast<int>(std::ceil(-min_y)) + pad * (min_y < 0);
  const int right =
      static_cast<int>(std::ceil(max_x - (camera.width - 1))) + pad * (max_x > camera.width - 1);
  const int bottom =
      static_cast<int>(std::ceil(max_y - (camera.height - 1))) + pad * (max_y > camera.height - 1);
  *offset = Eigen::Vector2d(left, top);
  *size = cv::Size(camera.width + left + right, camera.height + top + bottom);
}

double RadialFoldRadius(const Camera& camera) {
  if (camera.model == DistortionModel::kEquidistant) {
    // d/dtheta [theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)], scanned in steps of
    // 1e-4 rad up to a right angle, where the normalised radius tan(theta) ends.
    const double k1 = camera.distortion[0], k2 = camera.distortion[1], k3 = camera.distortion[2],
                 k4 = camera.distortion[3];
    for (double theta = 0; theta < 0.5 * M_PI; theta += 1e-4) {
      const double t2 = theta * theta;
      if (1 + t2 * (3 * k1 + t2 * (5 * k2 + t2 * (7 * k3 + t2 * 9 * k4))) <= 0) return std::tan(theta);
    }
    return std::numeric_limits<double>::infinity();
  }
  const double k1 = camera.distortion[0], k2 = camera.distortion[1], k3 = camera.distortion[4];
  // d/dr [r (1 + k1 r^2 + k2 r^4 + k3 r^6)], scanned in steps of 1e-3 up to r = 10 (a 168 degree
  // field of view: beyond any lens this polynomial model describes).
  for (double r = 0; r <= 10; r += 1e-3) {
    const double r2 = r * r;
    if (1 + 3 * k1 * r2 + 5 * k2 * r2 * r2 + 7 * k3 * r2 * r2 * r2 <= 0) return r;
  }
  return std::numeric_limits<double>::infinity();
}

bool FullViewIsWellDefined(const Camera& camera, const Eigen::Vector2d& offset, const cv::Size& size) {
  // The model must be one-to-one over the whole canvas (its corners are the farthest from the
  // principal point), and every border pixel of the stored image must come back from its
  // undistortion (it has none beyond the fold).
  const double fold = RadialFoldRadius(camera);
  for (const double x : {-offset.x(), size.width - 1 - offset.x()}) {
    for (const double y : {-offset.y(), size.height - 1 - offset.y()}) {
      if (!(std::hypot((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy) < fold)) return false;
    }
  }
  auto round_trips = [&](double x, double y) {
    const Eigen::Vector2d p(x, y);
    return (camera.DistortPixel(camera.UndistortPixel(p)) - p).norm() < 0.01;
  };
  for (int x = 0; x < camera.width; ++x) {
    if (!round_trips(x, 0) || !round_trips(x, camera.height - 1)) return false;
  }
  for (int y = 0; y < camera.height; ++y) {
    if (!round_trips(0, y) || !round_trips(camera.width - 1, y)) return false;
  }
  return true;
}

bool DetectionCanvas(const Camera& camera, UndistortView view, int pad, Eigen::Vector2d* offset,
                     cv::Size* size) {
  *offset = Eigen::Vector2d::Zero();
  *size = cv::Size(camera.width, camera.height);
  if (view != UndistortView::kFullView || !camera.HasDistortion()) return false;
  Eigen::Vector2d full_offset;
  cv::Size full_size;
  FullViewCanvas(camera, pad, &full_offset, &full_size);
  if (!FullViewIsWellDefined(camera, full_offset, full_size)) return false;
  *offset = full_offset;
  *size = full_size;
  return true;
}

bool SeenByStoredImage(const Camera& camera, const Eigen::Vector2d& p, double margin) {
  const Eigen::Vector2d d = camera.HasDistortion() ? camera.DistortPixel(p) : p;
  return d.x() >= margin && d.y() >= margin && d.x() <= camera.width - 1 - margin &&
         d.y() <= camera.height - 1 - margin;
}

Eigen::Vector3d PerspectiveSubView::Ray(const Eigen::Vector2d& pixel) const {
  return (view_R_camera.transpose() * Eigen::Vector3d((pixel.x() - cx) / fx, (pixel.y() - cy) / fy, 1))
      .normalized();
}

Eigen::Vector2d PerspectiveSubView::ToUndistorted(const Eigen::Vector2d& pixel) const {
  return (undistorted_H_view * pixel.homogeneous()).hnormalized();
}

std::vector<PerspectiveSubView> EquidistantSubViews(const Camera& camera, int margin) {
  if (camera.model != DistortionModel::kEquidistant) return {};
  // The rays the stored image sees: every 2 px inside, every pixel along the border.
  std::vector<cv::Point2d> pixels;
  for (int y = 0; y < camera.height; y += 2) {
    for (int x = 0; x < camera.width; x += 2) pixels.emplace_back(x, y);
  }
  for (int x = 0; x < camera.width; ++x) pixels.emplace_back(x, 0), pixels.emplace_back(x, camera.height - 1);
  for (int y = 0; y < camera.height; ++y) pixels.emplace_back(0, y), pixels.emplace_back(camera.width - 1, y);
  std::vector<cv::Point2d> normalised;
  const cv::Matx33d camera_matrix(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::fisheye::undistortPoints(pixels, normalised, camera_matrix, camera.DistortionCoefficients());
  std::vector<Eigen::Vector3d> rays;
  rays.reserve(normalised.size());
  double half_yaw = 0, half_pitch = 0;
  for (const cv::Point2d& n : normalised) {
    const Eigen::Vector3d ray = Eigen::Vector3d(n.x, n.y, 1).normalized();
    rays.push_back(ray);
    half_yaw = std::max(half_yaw, std::abs(std::atan2(ray.x(), ray.z())));
    half_pitch = std::max(half_pitch, std::abs(std::atan2(ray.y(), std::hypot(ray.x(), ray.z()))));
  }
  // An odd number of axes per direction, one on the optical axis, spaced so that the outermost
  // cells end at the field of view's edge.
  const double cell = kSubViewCellDeg * M_PI / 180;
  auto axis_angles = [&](double half) {
    const int m = std::max(0, static_cast<int>(std::ceil((half - 0.5 * cell) / cell)));
    const double step = m > 0 ? half / (m + 0.5) : 0;
    std::vector<double> angles;
    for (int i = -m; i <= m; ++i) angles.push_back(i * step);
    return angles;
  };
  std::vector<PerspectiveSubView> views;
  for (const double pitch : axis_angles(half_pitch)) {
    for (const double yaw : axis_angles(half_yaw)) {
      PerspectiveSubView view;
      view.axis =
          Eigen::Vector3d(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
      // x stays horizontal (perpendicular to the camera's y axis), y completes a right-handed frame.
      const Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(view.axis).normalized();
      view.view_R_camera.row(0) = x.transpose();
      view.view_R_camera.row(1) = view.axis.cross(x).transpose();
      view.view_R_camera.row(2) = view.axis.transpose();
      view.fx = kSubViewZoom * camera.fx;
      view.fy = kSubViewZoom * camera.fy;
      views.push_back(view);
    }
  }
  // Each sub-view's cell: the rays closest to its axis; its image is their bounding box plus margin.
  std::vector<Eigen::AlignedBox2d> boxes(views.size());
  for (const Eigen::Vector3d& ray : rays) {
    size_t best = 0;
    for (size_t k = 1; k < views.size(); ++k) {
      if (views[k].axis.dot(ray) > views[best].axis.dot(ray)) best = k;
    }
    const Eigen::Vector3d v = views[best].view_R_camera * ray;
    boxes[best].extend(Eigen::Vector2d(views[best].fx * v.x() / v.z(), views[best].fy * v.y() / v.z()));
  }
  std::vector<PerspectiveSubView> kept;
  const Eigen::Matrix3d K = camera.K();
  for (size_t k = 0; k < views.size(); ++k) {
    if (boxes[k].isEmpty()) continue;
    PerspectiveSubView view = views[k];
    const Eigen::Vector2d lo = boxes[k].min(), hi = boxes[k].max();
    view.cx = std::ceil(-lo.x()) + margin;
    view.cy = std::ceil(-lo.y()) + margin;
    view.size = cv::Size(static_cast<int>(std::ceil(hi.x() + view.cx)) + margin + 1,
                         static_cast<int>(std::ceil(hi.y() + view.cy)) + margin + 1);
    Eigen::Matrix3d view_K;
    view_K << view.fx, 0, view.cx, 0, view.fy, view.cy, 0, 0, 1;
    view.undistorted_H_view = K * view.view_R_camera.transpose() * view_K.inverse();
    kept.push_back(view);
  }
  return kept;
}

ImageUndistorter::ImageUndistorter(const Camera& camera, UndistortInterpolation interpolation,
                                   UndistortView view)
    : camera_(camera),
      interpolation_(interpolation == UndistortInterpolation::kCubic      ? cv::INTER_CUBIC
                     : interpolation == UndistortInterpolation::kLanczos4 ? cv::INTER_LANCZOS4
                                                                          : cv::INTER_LINEAR),
      border_mode_(cv::BORDER_CONSTANT),
      canvas_size_(camera.width, camera.height) {
  if (!camera.HasDistortion()) return;
  const cv::Matx33d camera_matrix(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Mat coefficients = camera.DistortionCoefficients();
  cv::Matx33d canvas_matrix = camera_matrix;
  // 3 px beyond the field of view: the reach of the detector's smoothing and Sobel support, so
  // that the canvas's own border is never next to a seen pixel.
  if (view == UndistortView::kFullView && !DetectionCanvas(camera, view, 3, &offset_, &canvas_size_)) {
    // A strong barrel lens given by k1 alone folds back before the stored image's corners: the
    // canvas would mirror the image and grow without bound (k1 = -0.25, k2 = 0 on 640 x 480 gave
    // 51258 x 43612 px). The same-size view is what this calibration can describe.
    LOG_FIRST_N(WARNING, 1) << DistortionModelName(camera.model) << " lens distortion (k1 "
                            << camera.distortion[0] << ", k2 " << camera.distortion[1]
                            << ") is not one-to-one over the stored image's field of view: detecting on the "
                               "undistorted image of the stored size";
  } else if (view == UndistortView::kFullView) {
    full_view_ = true;
    canvas_matrix(0, 2) += offset_.x();
    canvas_matrix(1, 2) += offset_.y();
    // The nearest border pixel of the stored image beyond it, not black: no step edge along the
    // border of the seen region for the detector to find (nor for a crossing edge's chain to
    // turn into).
    border_mode_ = cv::BORDER_REPLICATE;
    // 3 px of the margin are the detector's reach (as the canvas's pad); the rest lets a junction
    // at the edge of a sub-view's cell keep arms long enough to be found there.
    sub_views_ = EquidistantSubViews(camera, 32);
    for (const PerspectiveSubView& sub : sub_views_) {
      cv::Matx33d rotation, view_matrix(sub.fx, 0, sub.cx, 0, sub.fy, sub.cy, 0, 0, 1);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) rotation(r, c) = sub.view_R_camera(r, c);
      }
      sub_map_x_.emplace_back();
      sub_map_y_.emplace_back();
      // cv::fisheye's R maps the camera's rays into the rectified (here: the sub-view's) frame.
      cv::fisheye::initUndistortRectifyMap(camera_matrix, coefficients, rotation, view_matrix, sub.size,
                                           CV_32FC1, sub_map_x_.back(), sub_map_y_.back());
    }
  }
  // Float maps: the fixed-point CV_16SC2 maps quantise to 1/32 px.
  if (camera.model == DistortionModel::kEquidistant) {
    cv::fisheye::initUndistortRectifyMap(camera_matrix, coefficients, cv::Matx33d::eye(), canvas_matrix,
                                         canvas_size_, CV_32FC1, map_x_, map_y_);
  } else {
    cv::initUndistortRectifyMap(camera_matrix, coefficients, cv::noArray(), canvas_matrix, canvas_size_,
                                CV_32FC1, map_x_, map_y_);
  }
}

int ImageUndistorter::SubViewOf(const Eigen::Vector3d& ray) const {
  int best = 0;
  for (int k = 1; k < static_cast<int>(sub_views_.size()); ++k) {
    if (sub_views_[k].axis.dot(ray) > sub_views_[best].axis.dot(ray)) best = k;
  }
  return best;
}

bool ImageUndistorter::SubViewSees(int k, const Eigen::Vector2d& pixel, double margin) const {
  const cv::Mat& map_x = sub_map_x_.at(k);
  const cv::Mat& map_y = sub_map_y_.at(k);
  if (!(pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() <= map_x.cols - 1 && pixel.y() <= map_x.rows - 1)) {
    return false;
  }
  // The remap tables bilinearly: they are smooth, so this is the stored pixel to far below 0.01 px.
  const int x0 = std::min(static_cast<int>(pixel.x()), map_x.cols - 2);
  const int y0 = std::min(static_cast<int>(pixel.y()), map_x.rows - 2);
  const double ax = pixel.x() - x0, ay = pixel.y() - y0;
  auto at = [&](const cv::Mat& map) {
    const float* row0 = map.ptr<float>(y0);
    const float* row1 = map.ptr<float>(y0 + 1);
    return (1 - ay) * ((1 - ax) * row0[x0] + ax * row0[x0 + 1]) +
           ay * ((1 - ax) * row1[x0] + ax * row1[x0 + 1]);
  };
  const double x = at(map_x), y = at(map_y);
  return x >= margin && y >= margin && x <= camera_.width - 1 - margin && y <= camera_.height - 1 - margin;
}

cv::Mat ImageUndistorter::ApplySubView(int k, const cv::Mat& image) const {
  CHECK_EQ(image.cols, camera_.width);
  CHECK_EQ(image.rows, camera_.height);
  cv::Mat view;
  cv::remap(image, view, sub_map_x_.at(k), sub_map_y_.at(k), interpolation_, cv::BORDER_REPLICATE);
  return view;
}

cv::Mat ImageUndistorter::Apply(const cv::Mat& image) const {
  CHECK_EQ(image.cols, camera_.width);
  CHECK_EQ(image.rows, camera_.height);
  if (map_x_.empty()) return image;
  cv::Mat undistorted;
  cv::remap(image, undistorted, map_x_, map_y_, interpolation_, border_mode_, cv::Scalar::all(0));
  return undistorted;
}

}  // namespace sfm

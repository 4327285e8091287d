#include "backend/triangulation/line_triangulation.h"

#include <glog/logging.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <optional>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

double DistanceToLine(const Eigen::Vector3d& x, const Line3& line) {
  const Eigen::Vector3d offset = x - line.point;
  return (offset - line.direction.dot(offset) * line.direction).norm();
}

double Median(std::vector<double> values) {
  const size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  if (values.size() % 2 == 1) return values[half];
  return 0.5 * (values[half] + *std::max_element(values.begin(), values.begin() + half));
}

}  // namespace

std::optional<double> BackProjectOntoLine(const Eigen::Matrix3d& K, const Pose3& world_T_camera,
                                          const Eigen::Vector2d& pixel, const Line3& line) {
  const Eigen::Vector3d ray = (world_T_camera.rotation * (K.inverse() * pixel.homogeneous())).normalized();
  const double cos_angle = ray.dot(line.direction);
  const double sin_squared = 1 - cos_angle * cos_angle;
  if (!(sin_squared > 1e-18)) return std::nullopt;
  const Eigen::Vector3d w = world_T_camera.translation - line.point;
  return (line.direction.dot(w) - cos_angle * ray.dot(w)) / sin_squared;
}

const char* LineStatusName(LineStatus status) {
  switch (status) {
    case LineStatus::kOk:
      return "ok";
    case LineStatus::kTooFewViews:
      return "too_few_views";
    case LineStatus::kUnobservable:
      return "unobservable";
    case LineStatus::kLargeReprojectionError:
      return "large_reprojection_error";
    case LineStatus::kNoExtent:
      return "no_extent";
    case LineStatus::kBehindCamera:
      return "behind_camera";
    case LineStatus::kTooClose:
      return "too_close";
  }
  return "unknown";
}

Eigen::Vector4d BackProjectedPlane(const Eigen::Matrix3d& K, const LineView& view) {
  CHECK(view.p0 != view.p1) << "a junction segment of zero length";
  const Eigen::Vector3d l = view.p0.homogeneous().cross(view.p1.homogeneous());
  const Pose3 camera_T_world = view.world_T_camera.Inverse();
  const Eigen::Vector3d n_camera = K.transpose() * l;  // the plane's normal in the camera frame
  Eigen::Vector4d plane;
  plane << camera_T_world.RotationMatrix().transpose() * n_camera, camera_T_world.translation.dot(n_camera);
  return plane / n_camera.norm();
}

double MaxPlaneAngle(const std::vector<Eigen::Vector4d>& planes) {
  double largest = 0;
  for (size_t i = 0; i < planes.size(); ++i) {
    for (size_t j = i + 1; j < planes.size(); ++j) {
      const Eigen::Vector3d a = planes[i].head<3>();
      const Eigen::Vector3d b = planes[j].head<3>();
      largest = std::max(largest, std::atan2(a.cross(b).norm(), std::abs(a.dot(b))));
    }
  }
  return largest;
}

double MaxCentreSpreadAngle(const std::vector<Eigen::Vector4d>& planes,
                            const std::vector<Eigen::Vector3d>& centres, const Line3& line) {
  CHECK_EQ(planes.size(), centres.size());
  double largest = 0;
  for (const Eigen::Vector3d& centre : centres) {
    const double distance = DistanceToLine(centre, line);
    for (const Eigen::Vector4d& plane : planes) {
      const double off_plane = std::abs(plane.head<3>().dot(centre) + plane.w());
      if (!(distance > off_plane)) return kPi / 2;
      largest = std::max(largest, std::asin(off_plane / distance));
    }
  }
  return largest;
}

Line3 IntersectPlanes(const std::vector<Eigen::Vector4d>& planes, const Eigen::Vector3d& centre) {
  CHECK_GE(planes.size(), 2u) << "a line needs two planes";
  // n . X + d = 0 with X = X' + centre: n . X' + (d + n . centre) = 0.
  Eigen::MatrixXd A(planes.size(), 4);
  for (size_t i = 0; i < planes.size(); ++i) {
    A.row(i) << planes[i].head<3>().transpose(), planes[i].w() + planes[i].head<3>().dot(centre);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  // Two homogeneous points a, b spanning the null space give the Pluecker line (direction, moment)
  // = (a_w b - b_w a, a x b); its point nearest the origin is direction x moment / |direction|^2.
  const Eigen::Vector4d a = svd.matrixV().col(2);
  const Eigen::Vector4d b = svd.matrixV().col(3);
  const Eigen::Vector3d direction = a.w() * b.head<3>() - b.w() * a.head<3>();
  const Eigen::Vector3d moment = a.head<3>().cross(b.head<3>());
  Line3 line;
  line.point = direction.cross(moment) / direction.squaredNorm() + centre;
  line.direction = direction.normalized();
  return line;
}

double LineReprojectionError(const Eigen::Matrix3d& K, const std::vector<LineView>& views,
                             const Line3& line) {
  const Eigen::Matrix3d K_inverse_transpose = K.inverse().transpose();
  double largest = 0;
  for (const LineView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const Eigen::Vector3d l =
        K_inverse_transpose * (camera_T_world * line.point).cross(camera_T_world.rotation * line.direction);
    const double scale = l.head<2>().norm();
    largest = std::max({largest, std::abs(l.dot(view.p0.homogeneous())) / scale,
                        std::abs(l.dot(view.p1.homogeneous())) / scale});
  }
  return largest;
}

LineStatus TriangulateLine(const Eigen::Matrix3d& K, const std::vector<LineView>& views,
                           const LineTriangulationOptions& options, Line3* line) {
  CHECK(options.Check().ok()) << options.Check().message();
  if (views.size() < 2) return LineStatus::kTooFewViews;
  std::vector<Eigen::Vector4d> planes;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const LineView& view : views) {
    planes.push_back(BackProjectedPlane(K, view));
    centre += view.world_T_camera.translation;
  }
  if (!(MaxPlaneAngle(planes) > options.min_plane_angle_deg * kPi / 180)) return LineStatus::kUnobservable;
  const Line3 intersection = IntersectPlanes(planes, centre / static_cast<double>(views.size()));
  std::vector<Eigen::Vector3d> centres;
  for (const LineView& view : views) {
    centres.push_back(view.world_T_camera.translation);
    if (!(DistanceToLine(view.world_T_camera.translation, intersection) >= options.min_depth_m)) {
      return LineStatus::kTooClose;
    }
  }
  // The planes may differ by noise alone (short segments, centres nearly coincident: no motion
  // with noisy odometry); then the centres do not spread across them.
  if (!(MaxCentreSpreadAngle(planes, centres, intersection) > options.min_centre_spread_deg * kPi / 180)) {
    return LineStatus::kUnobservable;
  }
  if (!(LineReprojectionError(K, views, intersection) < options.max_reprojection_error_px)) {
    return LineStatus::kLargeReprojectionError;
  }
  *line = intersection;
  return LineStatus::kOk;
}

LineStatus BoundLine(const Eigen::Matrix3d& K, const std::vector<LineView>& views, const Line3& line,
                     const Eigen::Vector3d* junction_point, const LineTriangulationOptions& options,
                     Segment3* segment) {
  CHECK(options.Check().ok()) << options.Check().message();
  std::vector<double> near, far;
  double far_minus_near = 0;  // sum over views: positive when the far ends lie along +direction
  for (const LineView& view : views) {
    const std::optional<double> s_near = BackProjectOntoLine(K, view.world_T_camera, view.p0, line);
    const std::optional<double> s_far = BackProjectOntoLine(K, view.world_T_camera, view.p1, line);
    if (s_near) near.push_back(*s_near);
    if (s_far) far.push_back(*s_far);
    if (s_near && s_far) far_minus_near += *s_far - *s_near;
  }
  if (far.empty() || (junction_point == nullptr && near.empty())) return LineStatus::kNoExtent;
  const double sign = far_minus_near >= 0 ? 1 : -1;
  const double s0 =
      junction_point != nullptr ? (*junction_point - line.point).dot(line.direction) : Median(near);
  const double s1 = Median(far);
  if (!(sign * (s1 - s0) > 0)) return LineStatus::kNoExtent;
  const Segment3 bounded{line.point + s0 * line.direction, line.point + s1 * line.direction};
  bool too_close = false;
  for (const LineView& view : views) {
    const Pose3 camera_T_world = view.world_T_camera.Inverse();
    const double z0 = (camera_T_world * bounded.end0).z();
    const double z1 = (camera_T_world * bounded.end1).z();
    if (!(z0 > 0 && z1 > 0)) return LineStatus::kBehindCamera;
    if (!(z0 >= options.min_depth_m && z1 >= options.min_depth_m)) too_close = true;
  }
  if (too_close) return LineStatus::kTooClose;
  *segment = bounded;
  return LineStatus::kOk;
}

}  // namespace sfm

#include "tests/matching/synthetic_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Geometry>
#include <Eigen/LU>

namespace sfm::testing {

Eigen::Matrix3d TwoViews::F() const {
  const Pose3 camera2_T_camera1 = world_T_camera2.Inverse() * world_T_camera1;
  const Eigen::Vector3d t = camera2_T_camera1.translation;
  Eigen::Matrix3d t_cross;
  t_cross << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Matrix3d K_inverse = K.inverse();
  return K_inverse.transpose() * t_cross * camera2_T_camera1.RotationMatrix() * K_inverse;
}

Eigen::Vector2d TwoViews::Project(int camera, const Eigen::Vector3d& point_world) const {
  const Pose3& world_T_camera = camera == 0 ? world_T_camera1 : world_T_camera2;
  return (K * (world_T_camera.Inverse() * point_world)).hnormalized();
}

TwoViews MakeTwoViews() {
  TwoViews views;
  views.K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  views.world_T_camera1 = Pose3::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(3 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  views.world_T_camera2 = Pose3(R, Eigen::Vector3d(0.1, 0.0, 0.3));
  return views;
}

ProjectedJunction ProjectJunction(const TwoViews& views, int camera, const Junction3d& junction3d) {
  ProjectedJunction projected;
  projected.junction.location = views.Project(camera, junction3d.location);
  std::vector<Eigen::Vector2d> ends;
  for (const Eigen::Vector3d& end : junction3d.ends) ends.push_back(views.Project(camera, end));
  std::vector<double> angle;
  for (const Eigen::Vector2d& end : ends) {
    const Eigen::Vector2d d = end - projected.junction.location;
    angle.push_back(std::atan2(d.y(), d.x()));
  }
  projected.arm_of_segment.resize(ends.size());
  std::iota(projected.arm_of_segment.begin(), projected.arm_of_segment.end(), 0);
  std::sort(projected.arm_of_segment.begin(), projected.arm_of_segment.end(),
            [&](int x, int y) { return angle[x] < angle[y]; });
  // Detected segments of their own (ids unique in the process): detection gives two junctions one
  // line_segment only where they hold one segment, which the rivals-on-one-arm rule
  // reads; the arm is in arm_of_segment.
  static int next_line_segment = 0;
  for (const int arm : projected.arm_of_segment) {
    projected.junction.segments.push_back({ends[arm], next_line_segment++});
  }
  return projected;
}

bool IsWellShaped(const Junction& junction, const TwoViews& views, double min_length_px, double min_angle_deg) {
  auto inside = [&](const Eigen::Vector2d& p) {
    return p.x() >= 0 && p.y() >= 0 && p.x() <= views.width - 1 && p.y() <= views.height - 1;
  };
  if (!inside(junction.location)) return false;
  const int n = junction.NumSegments();
  for (int i = 0; i < n; ++i) {
    if (!inside(junction.segments[i].end)) return false;
    if ((junction.segments[i].end - junction.location).norm() < min_length_px) return false;
    const Eigen::Vector2d a = junction.SegmentDirection(i);
    const Eigen::Vector2d b = junction.SegmentDirection((i + 1) % n);
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    if (std::abs(turn) < min_angle_deg * M_PI / 180) return false;
  }
  return true;
}

void Perturb(Junction* junction, double min_px, double max_px, double location_sigma_px, std::mt19937* rng) {
  std::uniform_real_distribution<double> along(min_px, max_px);
  std::normal_distribution<double> noise(0, location_sigma_px);
  for (JunctionSegment& segment : junction->segments) {
    const Eigen::Vector2d n = (segment.end - junction->location).normalized();
    segment.end += along(*rng) * n;
  }
  junction->location += Eigen::Vector2d(noise(*rng), noise(*rng));
}

Junction3d RandomJunction3d(const TwoViews& views, int num_arms, std::mt19937* rng) {
  std::uniform_real_distribution<double> x(-2, 2), y(-1.4, 1.4), z(4, 8), length(0.4, 1.0);
  std::normal_distribution<double> gaussian(0, 1);
  while (true) {
    Junction3d junction3d;
    junction3d.location = Eigen::Vector3d(x(*rng), y(*rng), z(*rng));
    for (int k = 0; k < num_arms; ++k) {
      const Eigen::Vector3d direction = Eigen::Vector3d(gaussian(*rng), gaussian(*rng), gaussian(*rng)).normalized();
      junction3d.ends.push_back(junction3d.location + length(*rng) * direction);
    }
    if (IsWellShaped(ProjectJunction(views, 0, junction3d).junction, views, 20, 25) &&
        IsWellShaped(ProjectJunction(views, 1, junction3d).junction, views, 20, 25)) {
      return junction3d;
    }
  }
}

int TrueShift(const ProjectedJunction& a, const ProjectedJunction& b) {
  const int n = static_cast<int>(a.arm_of_segment.size());
  for (int shift = 0; shift < n; ++shift) {
    bool all = true;
    for (int i = 0; i < n; ++i) all = all && a.arm_of_segment[i] == b.arm_of_segment[(i + shift) % n];
    if (all) return shift;
  }
  return -1;
}

bool HasLineThrough(const Junction& junction, double max_deg) {
  const double max_sin = std::sin(max_deg * 3.14159265358979323846 / 180);
  for (size_t i = 0; i < junction.segments.size(); ++i) {
    for (size_t j = i + 1; j < junction.segments.size(); ++j) {
      const Eigen::Vector2d u = (junction.segments[i].end - junction.location).normalized();
      const Eigen::Vector2d v = (junction.segments[j].end - junction.location).normalized();
      if (u.dot(v) < 0 && std::abs(u.x() * v.y() - u.y() * v.x()) < max_sin) return true;
    }
  }
  return false;
}

}  // namespace sfm::testing

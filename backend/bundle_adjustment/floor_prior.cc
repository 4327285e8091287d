#include "backend/bundle_adjustment/floor_prior.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sfm {
namespace {

std::string Format(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

// A line's height when it is horizontal within half_width_m (its two ends' z differ by at most
// that), otherwise NaN.
double LineHeight(const LineLandmark& line, double half_width_m) {
  if (std::abs(line.end0.z() - line.end1.z()) > half_width_m) return std::nan("");
  return 0.5 * (line.end0.z() + line.end1.z());
}

bool InSlab(double z, double plane_z_m, double half_width_m) { return std::abs(z - plane_z_m) <= half_width_m; }

}  // namespace

std::string FloorPriorRigProblem(const Pose3& base_T_camera, const std::vector<Pose3>& world_T_base_odometry,
                                 double sigma_m) {
  const double camera_height_m = base_T_camera.translation.z();
  if (!(camera_height_m >= 10 * sigma_m)) {
    return "the camera is " + Format(camera_height_m) + " m above the base origin (T_base_camera), less than " +
           Format(10 * sigma_m) + " m";
  }
  const double max_tilt_rad = sigma_m / camera_height_m;
  for (size_t f = 0; f < world_T_base_odometry.size(); ++f) {
    const Pose3& pose = world_T_base_odometry[f];
    if (!(std::abs(pose.translation.z()) <= sigma_m)) {
      return "the odometry is not planar: frame " + std::to_string(f) + " has z = " +
             Format(pose.translation.z()) + " m (more than " + Format(sigma_m) + " m)";
    }
    const Eigen::Vector3d up = pose.rotation.normalized() * Eigen::Vector3d::UnitZ();
    const double tilt_rad = std::atan2(up.head<2>().norm(), up.z());
    if (!(tilt_rad <= max_tilt_rad)) {
      return "the odometry is not planar: frame " + std::to_string(f) + " has roll/pitch " + Format(tilt_rad) +
             " rad (more than " + Format(max_tilt_rad) + ")";
    }
  }
  return "";
}

namespace {

// The slab's centre moved from `centre` to the median of the heights it holds until it stays (at
// most 20 moves); nullopt when it holds none.
std::optional<double> SettleSlab(const std::vector<double>& sorted_heights, double centre, double half_width_m) {
  for (int iteration = 0; iteration < 20; ++iteration) {
    const auto first = std::lower_bound(sorted_heights.begin(), sorted_heights.end(), centre - half_width_m);
    const auto last = std::upper_bound(sorted_heights.begin(), sorted_heights.end(), centre + half_width_m);
    if (first == last) return std::nullopt;
    const double median = *(first + (last - first) / 2);
    if (median == centre) break;
    centre = median;
  }
  return centre;
}

}  // namespace

FloorPlane FindFloorPlane(const Landmarks& landmarks, double camera_z_m, double half_width_m, int min_support,
                          std::optional<double> around_z_m, std::optional<double> lowest_z_m) {
  std::vector<double> heights;
  auto consider = [&](double z) {  // false for NaN
    if (z < camera_z_m && !(lowest_z_m && z < *lowest_z_m)) heights.push_back(z);
  };
  for (const PointLandmark& point : landmarks.points) {
    if (!point.occlusion_candidate) consider(point.position.z());
  }
  for (const LineLandmark& line : landmarks.lines) consider(LineHeight(line, half_width_m));
  std::sort(heights.begin(), heights.end());
  FloorPlane plane;
  plane.below_camera = static_cast<int>(heights.size());
  const double width_m = 2 * half_width_m;
  const int needed = min_support;
  // The lowest window [heights[i], heights[i] + width] holding enough; then the slab is moved to
  // the median of what it holds until it stays (a window that starts on a few stray landmarks
  // below the floor holds only the floor's lower part, and its own median is too low).
  auto support = [&](double centre) {
    return static_cast<int>(
        std::count_if(heights.begin(), heights.end(), [&](double z) { return InSlab(z, centre, half_width_m); }));
  };
  if (around_z_m) {
    const std::optional<double> centre = SettleSlab(heights, *around_z_m, half_width_m);
    const int held = centre ? support(*centre) : 0;
    if (held >= needed) {
      plane.z_m = *centre;
      plane.support = held;
      plane.found = true;
      return plane;
    }
    plane.why = "fewer than " + std::to_string(needed) + " landmarks within " + Format(half_width_m) + " m of z = " +
                Format(*around_z_m) + " m";
    return plane;
  }
  size_t end = 0;
  for (size_t i = 0; i < heights.size(); ++i) {
    end = std::max(end, i);
    while (end < heights.size() && heights[end] <= heights[i] + width_m) ++end;
    if (static_cast<int>(end - i) < needed) continue;
    const double centre = *SettleSlab(heights, heights[i + (end - i) / 2], half_width_m);
    plane.z_m = centre;
    plane.support = support(centre);
    plane.found = true;
    return plane;
  }
  plane.why = "no horizontal plane below the cameras: no " + Format(width_m) + " m slab holds " +
              std::to_string(needed) + " of the " + std::to_string(heights.size()) + " landmarks below them";
  return plane;
}

FloorLandmarks SelectFloorLandmarks(const Landmarks& landmarks, double plane_z_m, double half_width_m) {
  FloorLandmarks selected;
  for (size_t i = 0; i < landmarks.points.size(); ++i) {
    if (landmarks.points[i].occlusion_candidate) continue;
    if (InSlab(landmarks.points[i].position.z(), plane_z_m, half_width_m)) {
      selected.points.push_back(static_cast<int>(i));
    }
  }
  for (size_t i = 0; i < landmarks.lines.size(); ++i) {
    const LineLandmark& line = landmarks.lines[i];
    if (InSlab(line.end0.z(), plane_z_m, half_width_m) && InSlab(line.end1.z(), plane_z_m, half_width_m)) {
      selected.lines.push_back(static_cast<int>(i));
    }
  }
  return selected;
}

void ScaleLandmarksAbout(const Eigen::Vector3d& centre, double gain, Landmarks* landmarks) {
  auto scaled = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return centre + gain * (x - centre); };
  for (PointLandmark& point : landmarks->points) point.position = scaled(point.position);
  for (LineLandmark& line : landmarks->lines) {
    line.point = scaled(line.point);
    line.end0 = scaled(line.end0);
    line.end1 = scaled(line.end1);
  }
}

double ParabolaMinimumStep(double cost_below, double cost_centre, double cost_above, double max_steps) {
  // c(x) = a x^2 + b x + c0 through (-1, below), (0, centre), (1, above).
  const double a = (cost_above + cost_below - 2 * cost_centre) / 2;
  const double b = (cost_above - cost_below) / 2;
  if (a > 0) return std::clamp(-b / (2 * a), -max_steps, max_steps);
  // Not convex: the three samples say nothing of a minimum beyond them; the lowest one.
  if (cost_below < cost_centre && cost_below <= cost_above) return -1;
  if (cost_above < cost_centre && cost_above < cost_below) return 1;
  return 0;
}

}  // namespace sfm

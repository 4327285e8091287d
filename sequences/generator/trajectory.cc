#include "sequences/generator/trajectory.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include <glog/logging.h>

namespace sfm {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct PlanarPose {
  double x = 0, y = 0, yaw = 0;
};

// A piece of path: `length` m with constant signed curvature (1/m, positive turns left).
struct Segment {
  double length = 0;
  double curvature = 0;
};

// Samples a path given segment by segment. Each segment is cut into equal steps no longer than
// `step` and turning no more than `max_turn`, so that segment ends fall on frames. Stops after
// `max_frames` poses, or when `keep_going` returns false for a pose (that pose is not kept), or
// when `next_segment` returns false.
std::vector<PlanarPose> SamplePath(const PlanarPose& start, double step, double max_turn, int max_frames,
                                   const std::function<bool(int, Segment*)>& next_segment,
                                   const std::function<bool(const PlanarPose&)>& keep_going) {
  std::vector<PlanarPose> poses;
  PlanarPose pose = start;
  Segment segment;
  for (int index = 0; next_segment(index, &segment); ++index) {
    double segment_step = step;
    if (segment.curvature != 0) segment_step = std::min(step, max_turn / std::abs(segment.curvature));
    const int steps = std::max(1, static_cast<int>(std::ceil(segment.length / segment_step - 1e-9)));
    const double ds = segment.length / steps;
    for (int k = 0; k < steps; ++k) {
      if (static_cast<int>(poses.size()) >= max_frames || !keep_going(pose)) return poses;
      poses.push_back(pose);
      // Exact motion along an arc (or a line) of length ds.
      const double turn = segment.curvature * ds;
      if (std::abs(turn) < 1e-12) {
        pose.x += ds * std::cos(pose.yaw);
        pose.y += ds * std::sin(pose.yaw);
      } else {
        const double radius = 1.0 / segment.curvature;
        pose.x += radius * (std::sin(pose.yaw + turn) - std::sin(pose.yaw));
        pose.y -= radius * (std::cos(pose.yaw + turn) - std::cos(pose.yaw));
      }
      pose.yaw += turn;
    }
  }
  if (static_cast<int>(poses.size()) < max_frames && keep_going(pose)) poses.push_back(pose);
  return poses;
}

// The straight and turns paths from the origin, heading +x, not yet centred on the lane.
std::vector<PlanarPose> LanePath(const TrajectoryOptions& o, int max_frames,
                                 const std::function<bool(const PlanarPose&)>& keep_going) {
  if (o.type == TrajectoryType::kStraight) {
    return SamplePath({}, o.step, o.max_turn_per_frame, max_frames,
                      [&](int, Segment* s) { *s = {o.step, 0}; return true; }, keep_going);
  }
  // Turns: a straight, a left bend of turn_angle, then straights between bends of twice that,
  // alternately right and left.
  const double k = 1.0 / o.turn_radius;
  return SamplePath({}, o.step, o.max_turn_per_frame, max_frames,
                    [&](int index, Segment* s) {
                      if (index % 2 == 0) {
                        *s = {o.turn_straight, 0};
                      } else if (index == 1) {
                        *s = {o.turn_angle * o.turn_radius, k};
                      } else {
                        const bool right = (index / 2) % 2 == 1;
                        *s = {2 * o.turn_angle * o.turn_radius, right ? -k : k};
                      }
                      return true;
                    },
                    keep_going);
}

double DistanceToBox(const Eigen::Vector2d& p, const Eigen::AlignedBox2d& box) {
  const Eigen::Vector2d nearest = p.cwiseMax(box.min()).cwiseMin(box.max());
  return (p - nearest).norm();
}

}  // namespace

bool ParseTrajectoryType(const std::string& name, TrajectoryType* type) {
  if (name == "straight") {
    *type = TrajectoryType::kStraight;
  } else if (name == "loop") {
    *type = TrajectoryType::kLoop;
  } else if (name == "turns") {
    *type = TrajectoryType::kTurns;
  } else {
    return false;
  }
  return true;
}

const char* TrajectoryTypeName(TrajectoryType type) {
  switch (type) {
    case TrajectoryType::kStraight: return "straight";
    case TrajectoryType::kLoop: return "loop";
    case TrajectoryType::kTurns: return "turns";
  }
  return "?";
}

Status TrajectoryOptions::Check() const {
  auto error = [](const std::string& what) { return Status::Error("trajectory options: " + what); };
  if (num_frames < 0 || num_frames > 100000) return error("num_frames must be in [0, 100000]");
  if (!(step >= 0.01 && step <= 2)) return error("step must be in [0.01, 2] m");
  if (!(max_turn_per_frame >= 0.005 && max_turn_per_frame <= 0.5)) {
    return error("max_turn_per_frame must be in [0.005, 0.5] rad");
  }
  if (!(start_margin >= 0 && end_margin >= 0)) return error("start_margin and end_margin must be >= 0");
  if (!std::isfinite(lane_offset)) return error("lane_offset must be finite");
  if (!(loop_margin > 0 && loop_corner_radius > 0)) return error("loop_margin and loop_corner_radius must be > 0");
  if (!(turn_angle > 0 && turn_angle < 1.5)) return error("turn_angle must be in (0, 1.5) rad");
  if (!(turn_radius > 0 && turn_straight >= 0)) return error("need turn_radius > 0 and turn_straight >= 0");
  if (!(robot_radius >= 0)) return error("robot_radius must be >= 0");
  return Status::Ok();
}

double TrajectoryExtentX(const TrajectoryOptions& options) {
  CHECK_GT(options.num_frames, 0);
  const std::vector<PlanarPose> path =
      LanePath(options, options.num_frames, [](const PlanarPose&) { return true; });
  double extent = 0;
  for (const PlanarPose& p : path) extent = std::max(extent, p.x);
  return extent;
}

Status MakeTrajectory(const TrajectoryOptions& options, const Scene& scene, std::vector<Pose3>* world_T_base) {
  CHECK(world_T_base != nullptr);
  SFM_RETURN_IF_ERROR(options.Check());
  const Eigen::Vector2d lo = scene.floor_min, hi = scene.floor_max;
  const int max_frames = options.num_frames > 0 ? options.num_frames : std::numeric_limits<int>::max();
  std::vector<PlanarPose> path;
  if (options.type == TrajectoryType::kLoop) {
    const double m = options.loop_margin, r = options.loop_corner_radius;
    const double side_x = hi.x() - lo.x() - 2 * m - 2 * r, side_y = hi.y() - lo.y() - 2 * m - 2 * r;
    if (side_x < 0 || side_y < 0) {
      std::ostringstream message;
      message << "trajectory: the loop does not fit on the floor: it needs at least " << 2 * (m + r)
              << " m each way (loop_margin " << m << ", loop_corner_radius " << r << "); use a room scene";
      return Status::Error(message.str());
    }
    const int lap_segments = 8;
    const int limit = options.num_frames > 0 ? std::numeric_limits<int>::max() : lap_segments;
    path = SamplePath({lo.x() + m + r, lo.y() + m, 0}, options.step, options.max_turn_per_frame, max_frames,
                      [&](int index, Segment* s) {
                        if (index >= limit) return false;
                        if (index % 2 == 1) {
                          *s = {0.5 * kPi * r, 1.0 / r};
                        } else {
                          *s = {(index / 2) % 2 == 0 ? side_x : side_y, 0};
                        }
                        return true;
                      },
                      [](const PlanarPose&) { return true; });
    // One lap ends where it started: drop the closing pose.
    if (options.num_frames == 0 && path.size() > 1) path.pop_back();
  } else {
    const double start_x = lo.x() + options.start_margin;
    const double end_x = hi.x() - options.end_margin;
    path = LanePath(options, max_frames, [&](const PlanarPose& p) {
      return options.num_frames > 0 || start_x + p.x <= end_x + 1e-9;
    });
    double min_y = 0, max_y = 0;
    for (const PlanarPose& p : path) {
      min_y = std::min(min_y, p.y);
      max_y = std::max(max_y, p.y);
    }
    const double shift_y = scene.lane_y + options.lane_offset - 0.5 * (min_y + max_y);
    for (PlanarPose& p : path) {
      p.x += start_x;
      p.y += shift_y;
    }
  }
  if (path.empty()) return Status::Error("trajectory: no pose fits on the floor");

  for (size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector2d p(path[i].x, path[i].y);
    const double rr = options.robot_radius;
    std::ostringstream where;
    where << "trajectory: frame " << i << " at (" << p.x() << ", " << p.y() << ") ";
    if (p.x() < lo.x() + rr || p.y() < lo.y() + rr || p.x() > hi.x() - rr || p.y() > hi.y() - rr) {
      return Status::Error(where.str() + "is within robot_radius of a wall (use fewer frames, a longer floor or "
                                         "a smaller step)");
    }
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const SceneObject& object = scene.objects[o];
      if (!object.obstacle || object.footprint.isEmpty()) continue;
      if (DistanceToBox(p, object.footprint) < rr) {
        return Status::Error(where.str() + "is within robot_radius of a " + object.kind + " (object " +
                             std::to_string(o) + "); change lane_offset or the seed");
      }
    }
  }
  world_T_base->clear();
  for (const PlanarPose& p : path) {
    world_T_base->push_back(
        Pose3(Eigen::Quaterniond(Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(p.x, p.y, 0)));
  }
  return Status::Ok();
}

}  // namespace sfm

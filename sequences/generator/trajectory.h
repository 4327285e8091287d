// Trajectories of a wheeled robot on the floor of a scene: poses world_T_base of the robot base
// (x forward, y left, z up; z = 0 on the floor), one per frame.
//
// - straight: forward along the scene's lane (the corridor's centre line, or 1.2 m off a room's
//   south wall), `step` apart.
// - loop: counter-clockwise around the room on a rounded rectangle `loop_margin` from the walls,
//   closing on itself (frame `lap` would coincide with frame 0).
// - turns: along the lane, weaving: bends that swing the heading `turn_angle` left and right
//   between short straights; the weave is centred on the lane.
// On bends the frames come closer so that the heading changes by at most `max_turn_per_frame`.
#pragma once

#include <string>
#include <vector>

#include "geometry/pose.h"
#include "util/status.h"
#include "sequences/generator/scene.h"

namespace sfm {

enum class TrajectoryType { kStraight, kLoop, kTurns };

// "straight" / "loop" / "turns"; false for any other name.
bool ParseTrajectoryType(const std::string& name, TrajectoryType* type);
const char* TrajectoryTypeName(TrajectoryType type);

struct TrajectoryOptions {
  TrajectoryType type = TrajectoryType::kStraight;
  int num_frames = 40;              // frames; 0: the whole path (loop: one lap; others: to the far end)
  double step = 0.2;                // m between frames on straight stretches
  double max_turn_per_frame = 0.1;  // rad, heading change between two frames on bends, at most
  double start_margin = 1.0;        // m, straight and turns start this far from the floor's low-x end
  double end_margin = 4.0;          // m, and keep this far from its high-x end (the view ahead stays deep)
  double lane_offset = 0;           // m, added to the scene's lane (positive: left)
  double loop_margin = 1.2;         // m, loop: distance of its straight sides from the walls
  double loop_corner_radius = 1.0;  // m, loop: radius of its rounded corners (0.1 m between frames there)
  double turn_angle = 0.3;          // rad, turns: the heading swings this far to either side
  double turn_radius = 2.0;         // m, turns: radius of the bends
  double turn_straight = 0.6;       // m, turns: straight stretch between two bends
  double robot_radius = 0.25;       // m, every pose keeps this far from the walls and furniture

  Status Check() const;
};

// The poses of the trajectory in the scene. Fails, naming the frame, when a pose comes closer
// than robot_radius to a wall or an obstacle, or the path does not fit on the floor.
Status MakeTrajectory(const TrajectoryOptions& options, const Scene& scene, std::vector<Pose3>* world_T_base);

// Length along x that a straight or turns trajectory of options.num_frames frames needs from its
// first to its last pose (m), for fitting a corridor to it. CHECKs num_frames > 0.
double TrajectoryExtentX(const TrajectoryOptions& options);

}  // namespace sfm

// Indoor polyhedral scenes for the synthetic generator: a corridor or a room (floor, ceiling, four
// walls) furnished along its walls with cabinets, shelves, box stacks, tables, door frames and
// posters, and (room) an island of a table and boxes in the middle. Sizes follow real buildings.
// Every face differs in brightness from the faces it meets by at least `min_contrast`, so each
// polygon border of the scene's wireframe is a real image edge.
#pragma once

#include <cstdint>

#include "util/status.h"
#include "sequences/generator/scene.h"

namespace sfm {

enum class SceneType { kCorridor, kRoom };

// "corridor" / "room"; false for any other name.
bool ParseSceneType(const std::string& name, SceneType* type);
const char* SceneTypeName(SceneType type);

struct SceneOptions {
  SceneType type = SceneType::kCorridor;
  // Corridor: floor x in [0, corridor_length], y in [-corridor_width / 2, corridor_width / 2].
  double corridor_length = 12.0;  // m; 0 (GenerateSequence only): fitted to the trajectory
  double corridor_width = 2.0;    // m
  // Room: floor x in [0, room_length], y in [0, room_width].
  double room_length = 7.0;  // m
  double room_width = 5.0;   // m
  double ceiling_height = 2.5;  // m, floor to ceiling

  double max_object_depth = 0.5;  // m, how far furniture reaches from its wall into the floor
  double object_gap_min = 0.15;   // m, free wall between two pieces of furniture, at least
  double object_gap_max = 0.9;    // m, at most
  bool ceiling_lights = true;     // bright flat panels on the ceiling
  bool island = true;             // room only: a table and a box stack in the middle of the room
  double min_contrast = 0.04;     // brightness step (0..1) across every edge, at least

  Lighting lighting;  // the light the contrast is measured under (the renderer uses the same)

  Status Check() const;
};

// Builds the scene; `seed` drives every random choice (sizes, positions, albedos). The same
// options and seed give the same scene bit for bit.
Status BuildScene(const SceneOptions& options, std::uint64_t seed, Scene* scene);

}  // namespace sfm

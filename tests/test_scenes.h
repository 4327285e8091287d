// Hand-built scenes for end-to-end tests: fixed geometry, so a test's frames stay the same while
// the random scene builder changes.
#pragma once

#include "sequences/generator/scene.h"

namespace sfm::testing {

// An empty room: floor [0, length] x [0, width] at z = 0 (albedo 0.35), ceiling at `height` (0.9),
// four walls of albedos 0.7, 0.6, 0.75, 0.65, normals facing the room's centre. Metres.
Scene RoomShell(double length, double width, double height);

}  // namespace sfm::testing

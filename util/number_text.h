// Numbers as text for every file the project writes (TUM, JSON, PLY, COLMAP).
#pragma once

#include <string>

namespace sfm {

// The shortest "%.{6..17}g" text that reads back to the same double, so files round-trip exactly
// and stay readable ("0.1", not "0.10000000000000001"). Negative zero is written "0": inverting a
// pose makes -0 from +0, and a file should not depend on that. Non-finite values give "nan",
// "inf" or "-inf" (for messages; writers of files that cannot hold them reject them first).
std::string ShortestNumberText(double value);

}  // namespace sfm

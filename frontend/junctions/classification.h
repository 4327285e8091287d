// Order and type of a junction's segments (paper section 2.2).
#pragma once

#include "frontend/junctions/junction.h"

namespace sfm {

// Sorts junction->segments clockwise as seen in the image. With pixel axes x right and y down,
// clockwise on screen is increasing atan2(dy, dx) of the direction from the location to the
// end-point; the first segment is the first clockwise from pointing left (atan2 = -pi).
void OrderClockwise(Junction* junction);

// The paper's type of a junction whose segments are in clockwise order: 2 segments L; 3 segments
// T when two of them are collinear (they come from one detected segment, or point within
// collinear_tolerance_rad of opposite ways), else ARROW when one angle between neighbours exceeds
// 180 degrees, else Y; 4 X; more N.
JunctionType ClassifyJunction(const Junction& junction, double collinear_tolerance_rad);

// OrderClockwise, then ClassifyJunction, with each segment's angle computed once for both: the
// same order and type.
JunctionType OrderClockwiseAndClassify(Junction* junction, double collinear_tolerance_rad);

}  // namespace sfm

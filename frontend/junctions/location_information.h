// How precisely a junction's location is known, direction by direction, from the lines through it.
#pragma once

#include <Eigen/Core>

#include "frontend/junctions/junction.h"

namespace sfm {

// The square root of the location's information matrix in units of one line fit's: each distinct
// line through the location fixes it across itself only, so the information is the sum of n n^T
// over the lines' unit normals n, and its square root whitens a location error
// (docs/bundle_adjustment.md, "Point observations"). Two perpendicular lines give the identity; two
// lines theta apart have 1 +- cos(theta): a 30 degree corner is known 2.7 times less well along its
// bisector than a right angle, and a little better across it. A T or an X may be an occlusion
// rather than a 3D junction (as tracks and the wireframe treat them): a T's location counts across
// its bar only (the occluding edge; where the stem meets it slides with the viewpoint), an X's not
// at all (either line may pass in front). Eigenvalues below min_information are raised to it.
Eigen::Matrix2d LocationSqrtInformation(const Junction& junction, double min_information = 0.01);

}  // namespace sfm

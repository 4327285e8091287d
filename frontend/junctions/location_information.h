// How precisely a junction's location is known, direction by direction, from the lines through it.
#pragma once

#include <Eigen/Core>

#include "frontend/junctions/junction.h"

namespace sfm {

// The square root of the location's information matrix in units of one line fit's: each distinct
// line through the location (a T's bar and an X's lines once) fixes the location across itself
// only, so the information is the sum of n n^T over the lines' unit normals n, and its square root
// whitens a location error (docs/bundle_adjustment.md, "Point observations"). Two perpendicular
// lines give the identity; two lines theta apart have 1 +- cos(theta): a 30 degree corner is known
// 2.7 times less well along its bisector than a right angle, and a little better across it.
// Eigenvalues below min_information are raised to it (a junction whose lines are nearly one line).
Eigen::Matrix2d LocationSqrtInformation(const Junction& junction, double min_information = 0.01);

}  // namespace sfm

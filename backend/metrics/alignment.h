// Rigid alignment of two point sets, the first step of the absolute trajectory error.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "frontend/geometry/pose.h"

namespace sfm {

// The rigid transform truth_T_estimated (rotation and translation, no scale) minimising
// sum_i |truth_i - T * estimated_i|^2, in closed form: the SVD of the cross-covariance with the
// reflection fix of Umeyama (1991, "Least-squares estimation of transformation parameters between
// two point patterns", eq. 38-43; Horn 1987 solves the same problem with quaternions).
// The two vectors must have the same length (CHECKed). Points in metres.
//
// Degenerate input: when the rotation is not determined, i.e. fewer than 3 points, or all points
// of either set (nearly) on one line (the cross-covariance has rank < 2, so any rotation about
// that line fits equally well), the alignment is translation-only: identity rotation and the
// translation that maps the centroid of `estimated` onto that of `truth` (the least-squares
// translation for a fixed rotation). No point at all gives the identity. `*rotation_determined`,
// when given, tells which case applied.
Pose3 AlignSE3(const std::vector<Eigen::Vector3d>& estimated, const std::vector<Eigen::Vector3d>& truth,
               bool* rotation_determined = nullptr);

}  // namespace sfm

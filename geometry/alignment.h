// Rigid alignment of two point sets, the first step of the absolute trajectory error.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/pose.h"

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

// A similarity: x -> scale * (rotation x) + translation, with rigid = (rotation, translation).
struct Similarity3 {
  double scale = 1;
  Pose3 rigid = Pose3::Identity();
  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const {
    return scale * (rigid.rotation * x) + rigid.translation;
  }
};

// The similarity truth_S_estimated minimising sum_i |truth_i - S * estimated_i|^2: Umeyama's
// (1991) eq. 40-42 with the scale, c = tr(D S) / sigma_e^2 (sigma_e^2 the mean squared distance of
// `estimated` from its centroid). It takes out what one camera cannot observe (the scale), so what
// is left is the shape of a trajectory. Degenerate input as AlignSE3 (the rotation then is the
// identity, the scale is still the least-squares one for that rotation); a set of one point, or of
// coincident points, has scale 1.
Similarity3 AlignSim3(const std::vector<Eigen::Vector3d>& estimated,
                      const std::vector<Eigen::Vector3d>& truth, bool* rotation_determined = nullptr);

}  // namespace sfm

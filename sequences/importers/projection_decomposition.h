// Decomposition of a 3x4 projection matrix x ~ P X into intrinsics and pose (Hartley and Zisserman,
// "Multiple View Geometry", 2nd ed., section 6.2.4: P = K [R | t] by an RQ decomposition of P's
// left 3x3 block).
#pragma once

#include <Eigen/Core>

#include "geometry/pose.h"
#include "util/status.h"

namespace sfm {

struct ProjectionDecomposition {
  Eigen::Matrix3d K;      // upper triangular, positive diagonal, K(2,2) = 1; K(0,1) is the skew
  Pose3 camera_T_world;   // R, t of P ~ K [R | t], det R = +1
  Eigen::Vector3d centre; // camera centre in the world, P (centre; 1) = 0
};

// P = lambda K [R | t] for any nonzero lambda of either sign: a P whose left 3x3 block has a
// negative determinant is negated first, since only then is R a rotation with a positive-diagonal K.
// P and -P project alike, so which side of the camera the scene lies on is not decided here: a
// caller whose world frame may have the other handedness checks its points' depths (see
// vgg_importer.h). Fails when P is not finite or its left 3x3 block is singular.
Status DecomposeProjection(const Eigen::Matrix<double, 3, 4>& P, ProjectionDecomposition* decomposition);

}  // namespace sfm

// Strecha et al. (CVPR 2008) multi-view benchmark folders, e.g. "entry-P10": images/NNNN.jpg and
// gt_dense_cameras/NNNN.jpg.camera with x ~ K R^T (X - C), metric, undistorted images.
#pragma once

#include <string>

#include "util/status.h"
#include "sequences/importers/imported_sequence.h"

namespace sfm {

// The pose and camera of one Strecha camera file: 26 numbers in 8 lines, K (3x3), radial
// distortion (3, zero for these undistorted images), R (3x3, columns are the camera axes in the
// world), C (camera centre in the world, metres), width and height. world_T_camera = (R, C).
struct StrechaCamera {
  Camera camera;
  Pose3 world_T_camera;
};

// Reads one camera file. Fails, naming the file, unless it holds exactly 26 finite numbers, K has
// the form (fx 0 cx; 0 fy cy; 0 0 1) with positive focal lengths, the distortion is zero, R is a
// rotation to the file's 6 digits (it is then made exactly orthonormal), and the size is positive
// whole pixels.
Status ReadStrechaCamera(const std::string& path, StrechaCamera* camera);

// Reads the folder: every gt_dense_cameras/<image>.camera, in name order, with its images/<image>.
// Fails, naming the file, on a missing folder, camera file or image, a malformed camera file, or a
// camera whose K or image size differs from the first one's (a sequence has one camera).
Status ReadStrechaSequence(const std::string& input_dir, ImportedSequence* sequence);

}  // namespace sfm

// Oxford VGG multi-view data (robots.ox.ac.uk/~vgg/data/data-mview.html), e.g. "Corridor":
// <name>.NNN.pgm images, <name>.NNN.P 3x4 camera matrices (x ~ P X, pixels in OpenCV's convention)
// and <name>.p3d 3D points, in a reconstruction whose units are not metres.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "frontend/util/status.h"
#include "sequences/importers/imported_sequence.h"

namespace sfm {

struct VggImportOptions {
  // The P matrices decompose to a K that differs from frame to frame, but a sequence has one K.
  // true: each pose is re-estimated for that shared K (PnP on the 3D points as P projects them), so
  // that K and pose together reproduce the images as well as one K can. false: each pose is R, C
  // of its own P's decomposition, which reproject with the shared K far worse (docs/importers.md).
  bool refit_poses = true;
  // true: each image is resampled to the shared K instead (H_i = K K_i^-1, shared_intrinsics_warp.h)
  // and cropped to the rectangle every warped frame covers; the poses are those of each P's own
  // decomposition, exactly right for the warped images, and refit_poses is not used. The data set's
  // own image measurements (bt.NNN.corners, .lines) then map to the sequence's pixels by the
  // per-frame affine maps of image_warps.txt.
  bool warp_to_shared_k = false;
};

struct VggImportSummary {
  // True when the files' world frame has the other handedness (P's left 3x3 block has det < 0 while
  // the scene is in front of the cameras): the sequence's world is then the point reflection of the
  // files' frame, X_world = -X_file. VggFileToWorld applies it.
  bool world_mirrored = false;
  // The sequence's K (median of the frames', skew 0; its principal point moved by the crop when warped).
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<double> refit_rms_px;  // per frame: RMS distance, shared K and pose vs P, over the 3D points used
  // With warp_to_shared_k, per frame: sequence pixel = A (source pixel; 1), before any scaling.
  std::vector<Eigen::Matrix<double, 2, 3>> source_to_image;
};

// Reads the VGG folder: every <name>.NNN.P with its <name>.NNN.pgm, in NNN order, and <name>.p3d.
// Fails, naming the file, on a missing folder or file, a P that is not 12 numbers or is singular,
// a point file that is not X Y Z triples, a camera with the scene behind it or fewer than 6 of the
// 3D points in view, and an undecodable first image (the others are decoded when written).
Status ReadVggSequence(const std::string& input_dir, const VggImportOptions& options, ImportedSequence* sequence,
                       VggImportSummary* summary);

// A point of the VGG files (.p3d, .l3d) in the imported sequence's world frame.
Eigen::Vector3d VggFileToWorld(const Eigen::Vector3d& point_in_file, bool world_mirrored);

}  // namespace sfm

// Oxford VGG multi-view data (robots.ox.ac.uk/~vgg/data/data-mview.html), e.g. "Corridor":
// <name>.NNN.pgm images, <name>.NNN.P 3x4 camera matrices (x ~ P X, pixels in OpenCV's convention)
// and <name>.p3d 3D points, in a reconstruction whose units are not metres.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "util/status.h"
#include "sequences/importers/imported_sequence.h"
#include "sequences/importers/plumb_line_distortion.h"
#include "sequences/importers/shared_camera_refit.h"

namespace sfm {

// How the poses are re-estimated for the sequence's one K (docs/importers.md, "VGG").
enum class VggRefit {
  // Every pose and every <name>.p3d point refitted together (a bundle adjustment,
  // shared_camera_refit.h) to the data set's matched corners (<name>.nview-corners,
  // <name>.NNN.corners), with K held at the median of the frames' decomposed K unless
  // refit_focal / refit_principal_point free it.
  kJoint,
  // Each pose fitted alone by PnP onto the fixed <name>.p3d points at the pixels its P projects
  // them to, for the median K .
  kPnpMedianK,
};

struct VggImportOptions {
  // The P matrices decompose to a K that differs from frame to frame, but a sequence has one K.
  // true: the poses are re-estimated for one shared K (by `refit`), so that K and poses together
  // reproduce the images as well as one K can. false: each pose is R, C of its own P's
  // decomposition with the median K, which reproject far worse (docs/importers.md).
  bool refit_poses = true;
  VggRefit refit = VggRefit::kJoint;
  // kJoint only: also estimate these (self-calibration). Off by default: on Corridor's forward
  // motion they are nearly unobservable and wander far outside the P files' range (fx 705, fy 1008
  // when free) for a small gain in reprojection error (docs/importers.md).
  bool refit_focal = false;
  bool refit_principal_point = false;
  bool refit_radial_k1 = false;  // written to sequence.yaml's distortion
  // kJoint only: the images' radial distortion (OpenCV's k1) when known from elsewhere, e.g. the
  // plumb-line check of docs/importers.md: held in the refit (the start when refit_radial_k1) and
  // written to sequence.yaml. 0: none, as the P files assume.
  double k1 = 0;
  // kJoint only: k1 instead by the plumb-line estimate (plumb_line_distortion.h) from the data set's
  // long straight segments, <name>.NNN.lines, in its images; held in the refit. Not with k1 != 0.
  // On by default (docs/importers.md, "VGG"): Corridor's images bow by 1-2.5 px along long edges. A
  // data set without .lines files or with too few long edges gets k1 = 0, with a warning and a note.
  bool k1_from_lines = true;
  bool warp_to_shared_k = false;
};

struct VggImportSummary {
  // True when the files' world frame has the other handedness (P's left 3x3 block has det < 0 while
  // the scene is in front of the cameras): the sequence's world is then the point reflection of the
  // files' frame, X_world = -X_file. VggFileToWorld applies it.
  bool world_mirrored = false;
  // The sequence's K (median of the frames', skew 0, unless the joint refit estimates it; its principal
  // point moved by the crop when warped).
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<double>
      refit_rms_px;  // per frame: RMS distance, shared K and PnP pose vs P, over the 3D points used
  // kJoint: the joint refit (K, k1, poses, points in the sequence's world, figures).
  std::optional<SharedCameraRefit> joint_refit;
  // k1_from_lines: the plumb-line estimate.
  std::optional<PlumbLineEstimate> plumb_line;
  // With warp_to_shared_k, per frame: sequence pixel = A (source pixel; 1), before any scaling.
  std::vector<Eigen::Matrix<double, 2, 3>> source_to_image;
};

// Reads the VGG folder: every <name>.NNN.P with its <name>.NNN.pgm, in NNN order, and <name>.p3d.
// Fails, naming the file, on a missing folder or file, a P that is not 12 numbers or is singular,
// a point file that is not X Y Z triples, a camera with the scene behind it or fewer than 6 of the
// 3D points in view, and an undecodable first image (the others are decoded when written). The
// joint refit (the default) also needs <name>.nview-corners (one row per 3D point, one corner index or
// '*' per view) and every <name>.NNN.corners ('x y' per line), and fails, naming the file, when they
// are missing or malformed.
Status ReadVggSequence(const std::string& input_dir, const VggImportOptions& options, ImportedSequence* sequence,
                       VggImportSummary* summary);

// A point of the VGG files (.p3d, .l3d) in the imported sequence's world frame.
Eigen::Vector3d VggFileToWorld(const Eigen::Vector3d& point_in_file, bool world_mirrored);

}  // namespace sfm

// report.html: one self-contained page about a junction_sfm run (docs/report.md), written into the
// output directory. Every figure is drawn by the project (plot.h, evaluation/match_overlay.h) and
// embedded as a base64 PNG data URI: no external script, font, style or image.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "geometry/pose.h"
#include "frontend/sequence/sequence.h"
#include "util/status.h"
#include "pipeline/pipeline_result.h"

namespace sfm {

// Writes <output_dir>/report.html atomically (the directory is created if needed). The page shows
// the run's headline figures, the trajectories from above, position and heading error along the
// sequence, junctions per frame, matches per frame pair, a few match pictures (paper Fig. 6) and
// the wireframe from above and from the side.
// `undistorted_images_or_empty`: the undistorted 8-bit images, one per frame, or empty, in which
// case the few frames the match pictures need are read from the sequence and undistorted here (a
// frame that cannot be read is reported on the page, not as an error). `stored_images_or_empty`:
// the frames as stored (8-bit grey), one per frame, so they are not read again; used when no
// undistorted images are given. Frames wider than 960 pixels are shrunk to that width for the match
// pictures (before the undistortion), so the page stays a few megabytes. Fails only when the file
// cannot be written.
Status WriteReport(const Sequence& sequence, const PipelineResult& result,
                   const std::vector<cv::Mat>& undistorted_images_or_empty, const std::string& output_dir,
                   const std::vector<cv::Mat>& stored_images_or_empty = {});

// The page WriteReport writes.
std::string ReportHtml(const Sequence& sequence, const PipelineResult& result,
                       const std::vector<cv::Mat>& undistorted_images_or_empty,
                       const std::vector<cv::Mat>& stored_images_or_empty = {});

// "data:image/png;base64,..." of an 8-bit image (grey or BGR): for plots, lossless.
std::string PngDataUri(const cv::Mat& image);
// "data:image/jpeg;base64,..." of an 8-bit image at JPEG quality kPhotoJpegQuality: for pictures
// of the frames, which PNG stores at about ten times the size and encodes several times slower.
inline constexpr int kPhotoJpegQuality = 92;
std::string JpegDataUri(const cv::Mat& image);

// The world axis (0 x, 1 y, 2 z) taken as vertical for the views from above and from the side: z
// (the generator's worlds have z up) when the camera positions spread least along it or by at most
// 5 cm, otherwise the axis along which they spread least (a ground robot moves in the horizontal).
int VerticalAxis(const std::vector<Pose3>& world_T_camera);

// The world's up direction (unit) for the wireframe views, from the robot's base frame: its z axis
// (up, docs/conventions.md) in the world, averaged over world_T_base = world_T_camera *
// base_T_camera^-1. Where the rig is the identity (a data set that gives camera poses directly) the
// base is the camera, and up is the camera's -y (OpenCV y points down in an upright camera).
// World z when there is no frame (or the average vanishes).
Eigen::Vector3d UpDirection(const std::vector<Pose3>& world_T_camera, const Pose3& base_T_camera);

// Error of an estimated trajectory per frame, after the alignment the ATE uses (AlignSE3 of the
// estimated camera positions onto the true ones): the position error |truth_i - T est_i| in
// metres, and the heading error in radians, (-pi, pi], positive counter-clockwise seen from above:
// the angle about the vertical axis from the true to the aligned estimated direction of the
// camera's optical axis (of its x axis when the optical axis is within 60 degrees of vertical in
// the first true pose). The two vectors must have the same length (CHECKed).
struct TrajectoryErrors {
  std::vector<double> position_m;
  std::vector<double> heading_rad;
};
TrajectoryErrors ComputeTrajectoryErrors(const std::vector<Pose3>& world_T_camera_estimated,
                                         const std::vector<Pose3>& world_T_camera_truth, int vertical_axis);

}  // namespace sfm

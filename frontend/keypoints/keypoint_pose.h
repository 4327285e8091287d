// A second source of a pair's correspondences, matched without any pose: ORB keypoints (OpenCV)
// matched by their descriptors (docs/matching.md, "Pose hypotheses"). The junction matcher's gates
// are centred on the odometry; where the odometry's error moves the epipolar lines by a period of
// a repeated pattern (a facade's windows), the gated junction matches pick the wrong copy and still
// fit a pose. The pose these correspondences fit is another centre for the gates.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "geometry/pose.h"

namespace sfm {

// One frame's keypoints: locations in undistorted pixels (the camera's K) and their ORB
// descriptors (one row each).
struct FrameKeypoints {
  std::vector<Eigen::Vector2d> locations;
  cv::Mat descriptors;
};

// Keypoints kept per frame: enough for dozens of correspondences a pair on 640x480 to 768x512
// images, few enough that the brute-force matching of a pair stays a few milliseconds.
constexpr int kKeypointsPerFrame = 1000;

// ORB keypoints of a frame of `camera` as LoadFrameImage decodes it (8-bit grey; CHECKed).
FrameKeypoints DetectKeypoints(const cv::Mat& image, const Camera& camera);

// Correspondences between two frames' keypoints: mutual nearest descriptors (Hamming) that pass
// Lowe's ratio test, x1[k] in a <-> x2[k] in b (undistorted pixels).
struct KeypointCorrespondences {
  std::vector<Eigen::Vector2d> x1, x2;
};
KeypointCorrespondences MatchKeypoints(const FrameKeypoints& a, const FrameKeypoints& b);

}  // namespace sfm

#include "frontend/keypoints/keypoint_pose.h"

#include <limits>

#include <glog/logging.h>

#include <opencv2/features2d.hpp>

namespace sfm {

namespace {

// Lowe's ratio: the best descriptor distance must be below this share of the second best.
constexpr double kRatio = 0.8;

}  // namespace

FrameKeypoints DetectKeypoints(const cv::Mat& image, const Camera& camera) {
  cv::Ptr<cv::ORB> orb = cv::ORB::create(kKeypointsPerFrame);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  CHECK_EQ(image.type(), CV_8UC1);
  orb->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  FrameKeypoints frame;
  frame.locations.reserve(keypoints.size());
  std::vector<int> kept;
  for (int k = 0; k < static_cast<int>(keypoints.size()); ++k) {
    const Eigen::Vector2d undistorted = camera.UndistortPixel({keypoints[k].pt.x, keypoints[k].pt.y});
    if (!undistorted.allFinite()) continue;
    frame.locations.push_back(undistorted);
    kept.push_back(k);
  }
  frame.descriptors.create(static_cast<int>(kept.size()), descriptors.cols, descriptors.type());
  for (int r = 0; r < static_cast<int>(kept.size()); ++r) descriptors.row(kept[r]).copyTo(frame.descriptors.row(r));
  return frame;
}

KeypointCorrespondences MatchKeypoints(const FrameKeypoints& a, const FrameKeypoints& b) {
  KeypointCorrespondences correspondences;
  if (a.locations.size() < 2 || b.locations.size() < 2) return correspondences;
  // Every Hamming distance once; both directions' nearest neighbours from it. Ties go to the lower
  // index, as OpenCV's brute-force matcher breaks them.
  cv::Mat distances;
  cv::batchDistance(a.descriptors, b.descriptors, distances, CV_32S, cv::noArray(), cv::NORM_HAMMING);
  const int rows = distances.rows, cols = distances.cols;
  constexpr int kNone = std::numeric_limits<int>::max();
  std::vector<int> best_a_of_b(cols, -1), best_distance_of_b(cols, kNone);
  std::vector<int> best_b(rows, -1), best(rows, kNone), second(rows, kNone);
  for (int i = 0; i < rows; ++i) {
    const int* row = distances.ptr<int>(i);
    for (int j = 0; j < cols; ++j) {
      const int d = row[j];
      if (d < second[i]) {
        if (d < best[i]) {
          second[i] = best[i];
          best[i] = d;
          best_b[i] = j;
        } else {
          second[i] = d;
        }
      }
      if (d < best_distance_of_b[j]) {
        best_distance_of_b[j] = d;
        best_a_of_b[j] = i;
      }
    }
  }
  for (int i = 0; i < rows; ++i) {
    // Lowe's ratio test on the two nearest, then the mutual check.
    if (!(best[i] < kRatio * second[i])) continue;
    const int j = best_b[i];
    if (best_a_of_b[j] != i) continue;
    correspondences.x1.push_back(a.locations[i]);
    correspondences.x2.push_back(b.locations[j]);
  }
  return correspondences;
}

}  // namespace sfm

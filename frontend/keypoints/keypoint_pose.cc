#include "frontend/keypoints/keypoint_pose.h"

#include <glog/logging.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

namespace sfm {

namespace {

// Lowe's ratio: the best descriptor distance must be below this share of the second best.
constexpr double kRatio = 0.8;

cv::Mat Grey8(const cv::Mat& image) {
  cv::Mat grey = image;
  if (grey.channels() == 3) cv::cvtColor(grey, grey, cv::COLOR_BGR2GRAY);
  if (grey.channels() == 4) cv::cvtColor(grey, grey, cv::COLOR_BGRA2GRAY);
  if (grey.depth() == CV_16U) grey.convertTo(grey, CV_8U, 1.0 / 257);
  return grey;
}

}  // namespace

FrameKeypoints DetectKeypoints(const cv::Mat& image, const Camera& camera) {
  cv::Ptr<cv::ORB> orb = cv::ORB::create(kKeypointsPerFrame);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(Grey8(image), cv::noArray(), keypoints, descriptors);
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
  const cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward, backward;
  matcher.knnMatch(a.descriptors, b.descriptors, forward, 2);
  matcher.knnMatch(b.descriptors, a.descriptors, backward, 1);
  for (const std::vector<cv::DMatch>& best : forward) {
    if (best.size() < 2 || best[0].distance >= kRatio * best[1].distance) continue;
    const int i = best[0].queryIdx, j = best[0].trainIdx;
    if (backward[j].empty() || backward[j][0].trainIdx != i) continue;  // mutual
    correspondences.x1.push_back(a.locations[i]);
    correspondences.x2.push_back(b.locations[j]);
  }
  return correspondences;
}

}  // namespace sfm

#include "frontend/batch/sequence_frontend.h"

#include <algorithm>
#include <map>

#include <glog/logging.h>
#include <opencv2/core.hpp>

#include "frontend/junctions/undistorted_junctions.h"
#include "util/parallel.h"

namespace sfm {

Status DetectSequenceJunctions(const Sequence& sequence, const ImageUndistorter& undistorter,
                               const SegmentDetectorOptions& segment_options,
                               const JunctionDetectorOptions& junction_options, Progress* progress,
                               std::vector<Junctions>* junctions, std::vector<TopologyGraph>* graphs,
                               std::vector<FrameKeypoints>* keypoints) {
  const int n = static_cast<int>(sequence.frames.size());
  junctions->assign(n, Junctions());
  graphs->assign(n, TopologyGraph());
  if (keypoints != nullptr) keypoints->assign(n, FrameKeypoints());
  std::vector<Status> statuses(n, Status::Ok());
  ParallelFor(n, [&](int i) {
    cv::Mat image;
    statuses[i] = LoadFrameImage(sequence, i, &image);
    if (statuses[i].ok()) {
      (*junctions)[i] = DetectUndistortedJunctions(undistorter, image, segment_options, junction_options);
      (*graphs)[i] = BuildTopologyGraph((*junctions)[i]);
      if (keypoints != nullptr) (*keypoints)[i] = DetectKeypoints(image, sequence.calibration.camera);
    }
    progress->Tick("junction detection", "frame", n);
  });
  progress->Finish();
  for (const Status& status : statuses) SFM_RETURN_IF_ERROR(status);
  return Status::Ok();
}

std::vector<KeypointCorrespondences> MatchConsecutiveKeypoints(const std::vector<std::pair<int, int>>& pairs,
                                                               const std::vector<FrameKeypoints>& keypoints) {
  std::vector<KeypointCorrespondences> correspondences(pairs.size());
  ParallelFor(static_cast<int>(pairs.size()), [&](int p) {
    const auto [a, b] = pairs[p];
    if (b == a + 1) correspondences[p] = MatchKeypoints(keypoints[a], keypoints[b]);
  });
  return correspondences;
}

std::vector<std::optional<Pose3>> KeypointPairPoses(const std::vector<PairGeometry>& geometries,
                                                             const std::vector<KeypointCorrespondences>& correspondences,
                                                             const PairRefinementSettings& settings) {
  CHECK_EQ(geometries.size(), correspondences.size());
  std::vector<std::optional<Pose3>> poses(geometries.size());
  ParallelFor(static_cast<int>(geometries.size()), [&](int p) {
    const KeypointCorrespondences& matches = correspondences[p];
    if (matches.x1.empty()) return;
    const PairRefinement refined = RefinePairGeometry(geometries[p], matches.x1, matches.x2, settings);
    if (!refined.Refined()) return;
    poses[p] = refined.geometry.camera2_T_camera1;
  });
  return poses;
}

void VerifySequencePairs(const std::vector<std::pair<int, int>>& pairs, const std::vector<PairGeometry>& geometries,
                         const std::vector<Junctions>& junctions, const std::vector<TopologyGraph>& graphs,
                         const MatchingOptions& options, Progress* progress, std::vector<FramePairMatches>* matches,
                         std::vector<MatchingDiagnostics>* diagnostics) {
  const int n = static_cast<int>(pairs.size());
  matches->assign(n, FramePairMatches());
  diagnostics->assign(n, MatchingDiagnostics());
  ParallelFor(n, [&](int p) {
    const auto [a, b] = pairs[p];
    (*matches)[p].frame_a = a;
    (*matches)[p].frame_b = b;
    (*matches)[p].matches = VerifiedFirstPass(junctions[a], graphs[a], junctions[b], graphs[b], geometries[p],
                                              options, &(*diagnostics)[p]);
    progress->Tick("matching, first pass", "pair", n);
  });
  progress->Finish();
}

void GuidedSequencePairs(const std::vector<Junctions>& junctions, const std::vector<TopologyGraph>& graphs,
                         const std::vector<PairGeometry>& geometries,
                         const std::vector<std::optional<Pose3>>& keypoint_poses,
                         const MatchingOptions& options, Progress* progress, std::vector<FramePairMatches>* matches,
                         std::vector<MatchingDiagnostics>* diagnostics) {
  const int n = static_cast<int>(matches->size());
  CHECK_EQ(diagnostics->size(), matches->size());
  CHECK(keypoint_poses.empty() || keypoint_poses.size() == matches->size());
  std::map<std::pair<int, int>, int> index_of_pair;
  for (int p = 0; p < n; ++p) index_of_pair[{(*matches)[p].frame_a, (*matches)[p].frame_b}] = p;
  // The pair's hypotheses: its keypoints' pose, and for a pair two frames apart the composition of
  // the two consecutive pairs' verified poses (their own pass has run by then).
  auto hypotheses_of = [&](int p) {
    std::vector<Pose3> hypotheses;
    if (!keypoint_poses.empty() && keypoint_poses[p]) hypotheses.push_back(*keypoint_poses[p]);
    const int a = (*matches)[p].frame_a, b = (*matches)[p].frame_b;
    const auto first = index_of_pair.find({a, a + 1});
    const auto second = index_of_pair.find({a + 1, b});
    if (b == a + 2 && first != index_of_pair.end() && second != index_of_pair.end()) {
      const PairRefinement& r1 = (*diagnostics)[first->second].refinement;
      const PairRefinement& r2 = (*diagnostics)[second->second].refinement;
      if (r1.Refined() && r2.Refined()) {
        hypotheses.push_back(r2.geometry.camera2_T_camera1 * r1.geometry.camera2_T_camera1);
      }
    }
    return hypotheses;
  };
  auto guided = [&](int p) {
    FramePairMatches& pair = (*matches)[p];
    const int a = pair.frame_a, b = pair.frame_b;
    pair.matches = GuidedPassOrHypotheses(junctions[a], graphs[a], junctions[b], graphs[b], std::move(pair.matches),
                                          geometries[p], hypotheses_of(p), options, &(*diagnostics)[p]);
    progress->Tick("matching, guided pass", "pair", n);
  };
  std::vector<int> consecutive, others;
  for (int p = 0; p < n; ++p) {
    ((*matches)[p].frame_b == (*matches)[p].frame_a + 1 ? consecutive : others).push_back(p);
  }
  ParallelFor(static_cast<int>(consecutive.size()), [&](int k) { guided(consecutive[k]); });
  ParallelFor(static_cast<int>(others.size()), [&](int k) { guided(others[k]); });
  progress->Finish();
}

std::vector<FramePairMatches> MatchSequencePairs(const std::vector<std::pair<int, int>>& pairs,
                                                 const std::vector<PairGeometry>& geometries,
                                                 const std::vector<Junctions>& junctions,
                                                 const std::vector<TopologyGraph>& graphs,
                                                 const MatchingOptions& options, Progress* progress,
                                                 std::vector<MatchingDiagnostics>* diagnostics,
                                                 const std::vector<std::optional<Pose3>>& keypoint_poses) {
  std::vector<FramePairMatches> matches;
  VerifySequencePairs(pairs, geometries, junctions, graphs, options, progress, &matches, diagnostics);
  GuidedSequencePairs(junctions, graphs, geometries, keypoint_poses, options, progress, &matches, diagnostics);
  return matches;
}

int RematchDisagreeingPairs(const std::vector<PairGeometry>& geometries, const std::vector<Junctions>& junctions,
                            const std::vector<TopologyGraph>& graphs, const MatchingOptions& options,
                            std::vector<FramePairMatches>* matches, std::vector<int>* inliers) {
  CHECK_EQ(geometries.size(), matches->size());
  if (inliers != nullptr) CHECK_EQ(inliers->size(), matches->size());
  std::vector<char> rematched(matches->size(), 0);
  ParallelFor(static_cast<int>(matches->size()), [&](int p) {
    FramePairMatches& pair = (*matches)[p];
    const int a = pair.frame_a, b = pair.frame_b;
    if (!MatchesDisagree(junctions[a], junctions[b], pair.matches, geometries[p], options)) return;
    MatchingDiagnostics diagnostics;
    const size_t before = pair.matches.size();
    pair.matches = MatchJunctions(junctions[a], graphs[a], junctions[b], graphs[b], geometries[p], options, &diagnostics);
    VLOG(1) << "pair " << a << "-" << b << " matched again: " << before << " -> " << pair.matches.size() << " matches";
    if (inliers != nullptr) (*inliers)[p] = diagnostics.refinement.inliers;
    rematched[p] = 1;
  });
  return static_cast<int>(std::count(rematched.begin(), rematched.end(), 1));
}

}  // namespace sfm

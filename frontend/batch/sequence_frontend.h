// The front end over a whole sequence on every core: each frame's junctions (paper section 2) and
// each pair's matches (sections 3-4) are computed alone, in parallel, each into its own slot, so
// the results are the same for any thread count (util/parallel.h).
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/junctions/junction_detector.h"
#include "frontend/junctions/topology.h"
#include "frontend/keypoints/keypoint_pose.h"
#include "frontend/matching/junction_matcher.h"
#include "frontend/matching/pair_geometry.h"
#include "frontend/segments/segment_detector.h"
#include "frontend/sequence/sequence.h"
#include "frontend/tracks/tracks.h"
#include "geometry/image_undistorter.h"
#include "util/progress.h"
#include "util/status.h"

namespace sfm {

// Junctions and topology graph of every frame, in undistorted pixels. Each frame is decoded when
// its detection starts and dropped when it ends: a thread holds one image at a time. An image
// that cannot be read fails the whole call with the error of the lowest such frame. keypoints (may
// be null) receives each frame's ORB keypoints (DetectKeypoints) from the same decoded image.
Status DetectSequenceJunctions(const Sequence& sequence, const ImageUndistorter& undistorter,
                               const SegmentDetectorOptions& segment_options,
                               const JunctionDetectorOptions& junction_options, Progress* progress,
                               std::vector<Junctions>* junctions, std::vector<TopologyGraph>* graphs,
                               std::vector<FrameKeypoints>* keypoints = nullptr);

// The keypoint correspondences (MatchKeypoints) of each consecutive pair of `pairs` (b = a + 1),
// empty for the others, which get the composition of the consecutive pairs' poses instead
// (GuidedSequencePairs). Kept instead of the keypoints: about a tenth of their memory.
std::vector<KeypointCorrespondences> MatchConsecutiveKeypoints(const std::vector<std::pair<int, int>>& pairs,
                                                               const std::vector<FrameKeypoints>& keypoints);

// Each pair's pose from its keypoint correspondences with geometries[p] as the prior
// (RefinePairGeometry); none where too few are within its gate, or where the pose leaves the
// prior's gate.
std::vector<std::optional<Pose3>> KeypointPairPoses(const std::vector<PairGeometry>& geometries,
                                                             const std::vector<KeypointCorrespondences>& correspondences,
                                                             const PairRefinementSettings& settings);

// The matches of every pair (frame a, frame b) of `pairs`, under geometries[p], in the order of
// `pairs`; diagnostics[p] receives the pair's refinement. keypoint_poses: empty, or per pair a
// hypothesis for GuidedPassOrHypotheses.
std::vector<FramePairMatches> MatchSequencePairs(const std::vector<std::pair<int, int>>& pairs,
                                                 const std::vector<PairGeometry>& geometries,
                                                 const std::vector<Junctions>& junctions,
                                                 const std::vector<TopologyGraph>& graphs,
                                                 const MatchingOptions& options, Progress* progress,
                                                 std::vector<MatchingDiagnostics>* diagnostics,
                                                 const std::vector<std::optional<Pose3>>& keypoint_poses = {});

// The same in MatchJunctions' two steps (VerifiedFirstPass, GuidedPass), every pair in parallel
// in each: VerifySequencePairs gives each pair's first-pass matches (in `matches`) and refinement
// (in diagnostics); GuidedSequencePairs continues them into MatchSequencePairs' result with
// GuidedPassOrHypotheses: the hypotheses are keypoint_poses[p] (when not empty) and, for a pair two
// frames apart, the composition of the two consecutive pairs' verified poses (those pairs first).
void VerifySequencePairs(const std::vector<std::pair<int, int>>& pairs, const std::vector<PairGeometry>& geometries,
                         const std::vector<Junctions>& junctions, const std::vector<TopologyGraph>& graphs,
                         const MatchingOptions& options, Progress* progress, std::vector<FramePairMatches>* matches,
                         std::vector<MatchingDiagnostics>* diagnostics);
void GuidedSequencePairs(const std::vector<Junctions>& junctions, const std::vector<TopologyGraph>& graphs,
                         const std::vector<PairGeometry>& geometries,
                         const std::vector<std::optional<Pose3>>& keypoint_poses,
                         const MatchingOptions& options, Progress* progress, std::vector<FramePairMatches>* matches,
                         std::vector<MatchingDiagnostics>* diagnostics);

// The pairs of `matches` whose matches disagree with geometries[p] (MatchesDisagree) matched again
// under it (MatchJunctions), each on its own (the same for any thread count); the others
// unchanged. geometries in the order of `matches`. inliers (may be null; one per pair): a pair
// matched again gets its new pose's inlier count. Returns how many were matched again.
int RematchDisagreeingPairs(const std::vector<PairGeometry>& geometries, const std::vector<Junctions>& junctions,
                            const std::vector<TopologyGraph>& graphs, const MatchingOptions& options,
                            std::vector<FramePairMatches>* matches, std::vector<int>* inliers = nullptr);

}  // namespace sfm

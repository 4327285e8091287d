#include "frontend/batch/sequence_frontend.h"

#include <glog/logging.h>
#include <opencv2/core.hpp>

#include "frontend/junctions/undistorted_junctions.h"
#include "util/parallel.h"

namespace sfm {

Status DetectSequenceJunctions(const Sequence& sequence, const ImageUndistorter& undistorter,
                               const SegmentDetectorOptions& segment_options,
                               const JunctionDetectorOptions& junction_options, Progress* progress,
                               std::vector<Junctions>* junctions, std::vector<TopologyGraph>* graphs) {
  const int n = static_cast<int>(sequence.frames.size());
  junctions->assign(n, Junctions());
  graphs->assign(n, TopologyGraph());
  std::vector<Status> statuses(n, Status::Ok());
  ParallelFor(n, [&](int i) {
    cv::Mat image;
    statuses[i] = LoadFrameImage(sequence, i, &image);
    if (statuses[i].ok()) {
      (*junctions)[i] = DetectUndistortedJunctions(undistorter, image, segment_options, junction_options);
      (*graphs)[i] = BuildTopologyGraph((*junctions)[i]);
    }
    progress->Tick("junction detection", "frame", n);
  });
  progress->Finish();
  for (const Status& status : statuses) SFM_RETURN_IF_ERROR(status);
  return Status::Ok();
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
                         const MatchingOptions& options, Progress* progress, std::vector<FramePairMatches>* matches,
                         std::vector<MatchingDiagnostics>* diagnostics) {
  const int n = static_cast<int>(matches->size());
  CHECK_EQ(diagnostics->size(), matches->size());
  ParallelFor(n, [&](int p) {
    FramePairMatches& pair = (*matches)[p];
    const int a = pair.frame_a, b = pair.frame_b;
    pair.matches = GuidedPass(junctions[a], graphs[a], junctions[b], graphs[b], std::move(pair.matches), options,
                              &(*diagnostics)[p]);
    progress->Tick("matching, guided pass", "pair", n);
  });
  progress->Finish();
}

std::vector<FramePairMatches> MatchSequencePairs(const std::vector<std::pair<int, int>>& pairs,
                                                 const std::vector<PairGeometry>& geometries,
                                                 const std::vector<Junctions>& junctions,
                                                 const std::vector<TopologyGraph>& graphs,
                                                 const MatchingOptions& options, Progress* progress,
                                                 std::vector<MatchingDiagnostics>* diagnostics) {
  std::vector<FramePairMatches> matches;
  VerifySequencePairs(pairs, geometries, junctions, graphs, options, progress, &matches, diagnostics);
  GuidedSequencePairs(junctions, graphs, options, progress, &matches, diagnostics);
  return matches;
}

}  // namespace sfm

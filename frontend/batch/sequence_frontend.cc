#include "frontend/batch/sequence_frontend.h"

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

std::vector<FramePairMatches> MatchSequencePairs(const std::vector<std::pair<int, int>>& pairs,
                                                 const std::vector<PairGeometry>& geometries,
                                                 const std::vector<Junctions>& junctions,
                                                 const std::vector<TopologyGraph>& graphs,
                                                 const MatchingOptions& options, Progress* progress,
                                                 std::vector<MatchingDiagnostics>* diagnostics) {
  const int n = static_cast<int>(pairs.size());
  std::vector<FramePairMatches> matches(n);
  diagnostics->assign(n, MatchingDiagnostics());
  ParallelFor(n, [&](int p) {
    const auto [a, b] = pairs[p];
    matches[p].frame_a = a;
    matches[p].frame_b = b;
    matches[p].matches = MatchJunctions(junctions[a], graphs[a], junctions[b], graphs[b], geometries[p],
                                        options, &(*diagnostics)[p]);
    progress->Tick("matching", "pair", n);
  });
  progress->Finish();
  return matches;
}

}  // namespace sfm

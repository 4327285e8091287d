// Tracks: pairwise junction matches joined across the sequence (union-find over (frame, junction)
// nodes), with the junction-segment correspondences carried along (union-find over (frame,
// junction, segment) nodes through each match's segment pairs, PartnerSegment). Partial matches
// (a junction of k segments with one of k + 1) are joined through their k pairs.
// docs/tracks_and_triangulation.md has the rules.
#pragma once

#include <utility>
#include <vector>

#include "frontend/junctions/junction.h"
#include "frontend/matching/matching_rule.h"

namespace sfm {

// The junction matches between two frames, as MatchJunctions returns them.
struct FramePairMatches {
  int frame_a = -1;                    // frame of JunctionMatch::index_a
  int frame_b = -1;                    // frame of JunctionMatch::index_b
  std::vector<JunctionMatch> matches;  // segment i of a <-> PartnerSegment(match, i, ...) of b
};

// One view of a junction track: the junction as seen in one frame.
struct TrackView {
  int frame = -1;             // index into the sequence's frames
  int junction = -1;          // index into that frame's Junctions (not its `id`)
  // segments[s]: this junction's segment index for the track's segment s, or -1 when this view's
  // junction has no segment in segment track s (a partial match left it out: an L seen where the
  // other views see a Y).
  std::vector<int> segments;
};

// A junction track: one 3D junction seen in several frames. Its segment s across the views
// (views[v].segments[s] for every v where it is not -1; at least two views) is a segment track:
// one 3D line seen as a junction segment.
struct JunctionTrack {
  int id = -1;                   // 0, 1, ... in order of the first view's (frame, junction)
  std::vector<TrackView> views;  // at least 2, at most one per frame, in increasing frame

  // The number of segment tracks (the size of every view's `segments`). With full matches only it
  // is every view's segment count N and view 0's segment s is the track's segment s. In general
  // the segment tracks are the segment components of the views' junctions that reach at least two
  // views, numbered in order of their first (view, segment); a junction segment that no match
  // paired is in none.
  int NumSegments() const { return static_cast<int>(views.front().segments.size()); }
};

// How the matches were used.
struct TrackBuildReport {
  int matches = 0;                     // matches given
  int accepted = 0;                    // joined into tracks
  int rejected_junction_conflict = 0;  // would have put two junctions of one frame in one track
  int rejected_segment_conflict = 0;  // segment pairs disagreeing with the track's: two segments of one frame
  int skipped_partial_occlusion = 0;  // partial matches with a T or an X on either side, not joined (below)
};

// The frame pairs to match so that tracks survive a junction missed in one frame: every
// consecutive pair (i-1, i) and every pair (i-2, i) two back, (a, b) with a < b, in increasing b
// then a. num_frames >= 0.
std::vector<std::pair<int, int>> FramePairsToMatch(int num_frames);

// Junction tracks from pairwise matches. frames[f] are the junctions of frame f; the matches must
// index them and be full (equal segment counts N, shift in [0, N)) or partial (counts k and k + 1,
// missing_a or missing_b a segment of the larger one, shift in [0, k)); all CHECKed, as
// MatchJunctions guarantees.
//
// Matches are taken strongest first (decreasing similarity, ties in input order). A match is
// accepted when it keeps every track consistent: the two junctions' tracks share no frame, and
// none of its segment pairs (segment i of a <-> PartnerSegment(match, i, ...) of b; N pairs, or k
// for a partial match) joins two segments of one frame; otherwise it is rejected and counted. So an
// inconsistent component is never formed: it is split where its weakest conflicting match was. Components of
// a single junction are not tracks.
//
// A partial match with a T or an X on either side is not joined (skipped_partial_occlusion): a T
// or an X may be where a nearer edge cuts a farther one, which slides along the edges as the
// camera moves and is no 3D point, and a partial match is exactly what such a crossing gives when
// one of its arms is hidden in the other frame (an L against a T). Tracks are for triangulation;
// the pair's matches (matches/*.csv) keep them. Full matches of T's and X's are joined as before.
std::vector<JunctionTrack> BuildTracks(const std::vector<Junctions>& frames,
                                       const std::vector<FramePairMatches>& pairs,
                                       TrackBuildReport* report = nullptr);

}  // namespace sfm

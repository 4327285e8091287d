#include "frontend/tracks/tracks.h"

#include <glog/logging.h>

#include <algorithm>
#include <map>

#include "frontend/tracks/frame_union_find.h"

namespace sfm {
namespace {

// A T or an X: a crossing that may be an occlusion rather than a 3D junction (BuildTracks).
bool MayBeAnOcclusion(const Junction& junction) {
  return junction.type == JunctionType::kT || junction.type == JunctionType::kX;
}

// Node numbering of the two union-finds: junction (f, j) is junction_node[f][j]; its segment i is
// segment_node[f][j] + i.
struct NodeIndex {
  std::vector<std::vector<int>> junction_node;
  std::vector<std::vector<int>> segment_node;
  std::vector<int> junction_frames;  // frame of each junction node
  std::vector<int> segment_frames;   // frame of each segment node

  explicit NodeIndex(const std::vector<Junctions>& frames) {
    junction_node.resize(frames.size());
    segment_node.resize(frames.size());
    for (size_t f = 0; f < frames.size(); ++f) {
      for (const Junction& junction : frames[f]) {
        junction_node[f].push_back(static_cast<int>(junction_frames.size()));
        junction_frames.push_back(static_cast<int>(f));
        segment_node[f].push_back(static_cast<int>(segment_frames.size()));
        segment_frames.insert(segment_frames.end(), junction.segments.size(), static_cast<int>(f));
      }
    }
  }
};

// A match with its frames, as one unit of the greedy join.
struct FrameMatch {
  int frame_a, frame_b;
  JunctionMatch match;
};

void CheckMatch(const std::vector<Junctions>& frames, const FrameMatch& m) {
  const int num_frames = static_cast<int>(frames.size());
  CHECK(m.frame_a >= 0 && m.frame_a < num_frames && m.frame_b >= 0 && m.frame_b < num_frames &&
        m.frame_a != m.frame_b)
      << "match between frames " << m.frame_a << " and " << m.frame_b << " of " << num_frames;
  const Junctions& a = frames[m.frame_a];
  const Junctions& b = frames[m.frame_b];
  CHECK(m.match.index_a >= 0 && m.match.index_a < static_cast<int>(a.size()) && m.match.index_b >= 0 &&
        m.match.index_b < static_cast<int>(b.size()))
      << "match (" << m.match.index_a << ", " << m.match.index_b << ") outside frames " << m.frame_a << " ("
      << a.size() << " junctions) and " << m.frame_b << " (" << b.size() << ")";
  const int n_a = a[m.match.index_a].NumSegments();
  const int n_b = b[m.match.index_b].NumSegments();
  if (!m.match.Partial()) {
    CHECK_EQ(n_a, n_b) << "full match between junctions with different segment counts";
  } else if (m.match.missing_a >= 0 && m.match.missing_b >= 0) {
    // One common segment (docs/matching.md): two L's, one unshared segment each.
    CHECK(n_a == 2 && n_b == 2) << "match with two missing segments between junctions of " << n_a << " and "
                                << n_b << " segments";
    CHECK(m.match.missing_a < 2 && m.match.missing_b < 2 && m.match.shift == 0)
        << "bad one-common-segment match";
    return;
  } else {
    // Partial: exactly one side names its left-out segment, and that side has one segment more.
    const int n_larger = m.match.missing_a >= 0 ? n_a : n_b;
    const int missing = m.match.missing_a >= 0 ? m.match.missing_a : m.match.missing_b;
    CHECK_EQ(n_larger, (m.match.missing_a >= 0 ? n_b : n_a) + 1)
        << "partial match between junctions of " << n_a << " and " << n_b << " segments";
    CHECK(missing < n_larger) << "missing segment " << missing << " of " << n_larger;
  }
  const int k = std::min(n_a, n_b);
  CHECK(m.match.shift >= 0 && m.match.shift < k) << "shift " << m.match.shift << " for " << k << " segments";
}

}  // namespace

std::vector<std::pair<int, int>> FramePairsToMatch(int num_frames) {
  CHECK_GE(num_frames, 0);
  std::vector<std::pair<int, int>> pairs;
  for (int b = 1; b < num_frames; ++b) {
    if (b >= 2) pairs.emplace_back(b - 2, b);
    pairs.emplace_back(b - 1, b);
  }
  return pairs;
}

std::vector<JunctionTrack> BuildTracks(const std::vector<Junctions>& frames,
                                       const std::vector<FramePairMatches>& pairs, TrackBuildReport* report) {
  std::vector<FrameMatch> matches;
  for (const FramePairMatches& pair : pairs) {
    for (const JunctionMatch& match : pair.matches) {
      matches.push_back({pair.frame_a, pair.frame_b, match});
      CheckMatch(frames, matches.back());
    }
  }
  std::stable_sort(matches.begin(), matches.end(), [](const FrameMatch& x, const FrameMatch& y) {
    return x.match.similarity > y.match.similarity;
  });

  const NodeIndex nodes(frames);
  FrameUnionFind junction_sets(nodes.junction_frames);
  FrameUnionFind segment_sets(nodes.segment_frames);
  TrackBuildReport counts;
  counts.matches = static_cast<int>(matches.size());
  for (const FrameMatch& m : matches) {
    const Junction& junction_a = frames[m.frame_a][m.match.index_a];
    const Junction& junction_b = frames[m.frame_b][m.match.index_b];
    if (m.match.Partial() && (MayBeAnOcclusion(junction_a) || MayBeAnOcclusion(junction_b))) {
      ++counts.skipped_partial_occlusion;
      continue;
    }
    const int node_a = nodes.junction_node[m.frame_a][m.match.index_a];
    const int node_b = nodes.junction_node[m.frame_b][m.match.index_b];
    if (!junction_sets.CanUnion(node_a, node_b)) {
      ++counts.rejected_junction_conflict;
      continue;
    }
    // The match's segment pairs (first_a + i, first_b + partner). Segment components never span
    // two junction components, and a match's pairs join distinct components on each side, so each
    // pair can be tested alone.
    const int n_a = frames[m.frame_a][m.match.index_a].NumSegments();
    const int n_b = frames[m.frame_b][m.match.index_b].NumSegments();
    const int first_a = nodes.segment_node[m.frame_a][m.match.index_a];
    const int first_b = nodes.segment_node[m.frame_b][m.match.index_b];
    std::vector<std::pair<int, int>> segment_pairs;
    for (int i = 0; i < n_a; ++i) {
      const int partner = PartnerSegment(m.match, i, n_a, n_b);
      if (partner >= 0) segment_pairs.emplace_back(first_a + i, first_b + partner);
    }
    const bool segments_agree =
        std::all_of(segment_pairs.begin(), segment_pairs.end(),
                    [&](const std::pair<int, int>& p) { return segment_sets.CanUnion(p.first, p.second); });
    if (!segments_agree) {
      ++counts.rejected_segment_conflict;
      continue;
    }
    junction_sets.Union(node_a, node_b);
    for (const auto& [segment_a, segment_b] : segment_pairs) segment_sets.Union(segment_a, segment_b);
    ++counts.accepted;
  }

  // Components in order of their first (frame, junction); members in increasing frame.
  std::vector<std::vector<std::pair<int, int>>> members_of_root(
      junction_sets.NumNodes());  // (frame, junction)
  std::vector<int> root_order;
  for (size_t f = 0; f < frames.size(); ++f) {
    for (size_t j = 0; j < frames[f].size(); ++j) {
      const int root = junction_sets.Find(nodes.junction_node[f][j]);
      if (members_of_root[root].empty()) root_order.push_back(root);
      members_of_root[root].emplace_back(static_cast<int>(f), static_cast<int>(j));
    }
  }

  std::vector<JunctionTrack> tracks;
  for (int root : root_order) {
    const std::vector<std::pair<int, int>>& members = members_of_root[root];
    if (members.size() < 2) continue;
    JunctionTrack track;
    track.id = static_cast<int>(tracks.size());
    // The segment tracks: the components of the members' segments that reach two views, numbered in
    // order of their first (view, segment); with full matches only, view 0's segment s is track
    // segment s.
    std::map<int, int> views_of_root;
    for (const auto& [frame, junction] : members) {
      for (int i = 0; i < frames[frame][junction].NumSegments(); ++i) {
        ++views_of_root[segment_sets.Find(nodes.segment_node[frame][junction] + i)];
      }
    }
    std::map<int, int> track_segment_of_root;
    for (const auto& [frame, junction] : members) {
      for (int i = 0; i < frames[frame][junction].NumSegments(); ++i) {
        const int root = segment_sets.Find(nodes.segment_node[frame][junction] + i);
        if (views_of_root[root] >= 2 && !track_segment_of_root.count(root)) {
          const int s = static_cast<int>(track_segment_of_root.size());
          track_segment_of_root[root] = s;
        }
      }
    }
    const int num_segments = static_cast<int>(track_segment_of_root.size());
    for (const auto& [frame, junction] : members) {
      TrackView view;
      view.frame = frame;
      view.junction = junction;
      view.segments.assign(num_segments, -1);
      for (int i = 0; i < frames[frame][junction].NumSegments(); ++i) {
        const auto it =
            track_segment_of_root.find(segment_sets.Find(nodes.segment_node[frame][junction] + i));
        if (it != track_segment_of_root.end()) view.segments[it->second] = i;
      }
      track.views.push_back(std::move(view));
    }
    tracks.push_back(std::move(track));
  }
  if (report != nullptr) *report = counts;
  return tracks;
}

}  // namespace sfm

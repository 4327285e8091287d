#include "frontend/tracks/tracks.h"

#include <glog/logging.h>

#include <algorithm>
#include <map>

#include "frontend/tracks/frame_union_find.h"

namespace sfm {
namespace {

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
  const int n = a[m.match.index_a].NumSegments();
  CHECK_EQ(n, b[m.match.index_b].NumSegments()) << "matched junctions with different segment counts";
  CHECK(m.match.shift >= 0 && m.match.shift < n) << "shift " << m.match.shift << " for " << n << " segments";
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
    const int node_a = nodes.junction_node[m.frame_a][m.match.index_a];
    const int node_b = nodes.junction_node[m.frame_b][m.match.index_b];
    if (!junction_sets.CanUnion(node_a, node_b)) {
      ++counts.rejected_junction_conflict;
      continue;
    }
    // Segment components never span two junction components, so each pairing can be tested alone.
    const int n = frames[m.frame_a][m.match.index_a].NumSegments();
    const int first_a = nodes.segment_node[m.frame_a][m.match.index_a];
    const int first_b = nodes.segment_node[m.frame_b][m.match.index_b];
    bool segments_agree = true;
    for (int i = 0; i < n && segments_agree; ++i) {
      segments_agree = segment_sets.CanUnion(first_a + i, first_b + (i + m.match.shift) % n);
    }
    if (!segments_agree) {
      ++counts.rejected_segment_conflict;
      continue;
    }
    junction_sets.Union(node_a, node_b);
    for (int i = 0; i < n; ++i) segment_sets.Union(first_a + i, first_b + (i + m.match.shift) % n);
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
    // The track's segment s is the segment component of view 0's segment s.
    const auto [frame0, junction0] = members.front();
    const int n = frames[frame0][junction0].NumSegments();
    std::map<int, int> track_segment_of_root;
    for (int s = 0; s < n; ++s) {
      track_segment_of_root[segment_sets.Find(nodes.segment_node[frame0][junction0] + s)] = s;
    }
    for (const auto& [frame, junction] : members) {
      TrackView view;
      view.frame = frame;
      view.junction = junction;
      view.segments.assign(n, -1);
      for (int i = 0; i < n; ++i) {
        const auto it =
            track_segment_of_root.find(segment_sets.Find(nodes.segment_node[frame][junction] + i));
        CHECK(it != track_segment_of_root.end()) << "segment outside the track's segment tracks";
        view.segments[it->second] = i;
      }
      track.views.push_back(std::move(view));
    }
    tracks.push_back(std::move(track));
  }
  if (report != nullptr) *report = counts;
  return tracks;
}

}  // namespace sfm

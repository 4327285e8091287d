#include "frontend/tracks/frame_union_find.h"

#include <glog/logging.h>

#include <algorithm>
#include <iterator>
#include <utility>

namespace sfm {
namespace {

bool SortedIntersect(const std::vector<int>& a, const std::vector<int>& b) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    if (*i < *j) {
      ++i;
    } else {
      ++j;
    }
  }
  return false;
}

}  // namespace

FrameUnionFind::FrameUnionFind(std::vector<int> node_frames) : parent_(node_frames.size()) {
  frames_.reserve(node_frames.size());
  for (size_t i = 0; i < node_frames.size(); ++i) {
    parent_[i] = static_cast<int>(i);
    frames_.push_back({node_frames[i]});
  }
}

int FrameUnionFind::Find(int node) {
  CHECK(node >= 0 && node < NumNodes()) << "node " << node << " of " << NumNodes();
  while (parent_[node] != node) {
    parent_[node] = parent_[parent_[node]];
    node = parent_[node];
  }
  return node;
}

bool FrameUnionFind::CanUnion(int a, int b) {
  const int root_a = Find(a);
  const int root_b = Find(b);
  return root_a == root_b || !SortedIntersect(frames_[root_a], frames_[root_b]);
}

void FrameUnionFind::Union(int a, int b) {
  CHECK(CanUnion(a, b)) << "nodes " << a << " and " << b << " have components sharing a frame";
  int root_a = Find(a);
  int root_b = Find(b);
  if (root_a == root_b) return;
  if (frames_[root_a].size() < frames_[root_b].size()) std::swap(root_a, root_b);
  std::vector<int> merged;
  merged.reserve(frames_[root_a].size() + frames_[root_b].size());
  std::merge(frames_[root_a].begin(), frames_[root_a].end(), frames_[root_b].begin(), frames_[root_b].end(),
             std::back_inserter(merged));
  frames_[root_a] = std::move(merged);
  frames_[root_b] = {};
  parent_[root_b] = root_a;
}

}  // namespace sfm

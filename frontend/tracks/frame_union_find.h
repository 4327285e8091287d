// Union-find over nodes that each belong to one frame, refusing any union that would put two nodes
// of one frame into one component: the consistency rule of tracks (a track sees a thing at most
// once per frame).
#pragma once

#include <vector>

namespace sfm {

class FrameUnionFind {
 public:
  // One node per entry, node i in frame node_frames[i]; every node starts as its own component.
  explicit FrameUnionFind(std::vector<int> node_frames);

  int NumNodes() const { return static_cast<int>(parent_.size()); }
  // The representative of node's component (path halving; amortised near O(1)).
  int Find(int node);
  // True when a and b are in one component already, or their components share no frame.
  bool CanUnion(int a, int b);
  // Joins the components of a and b; CanUnion(a, b) must hold (CHECKed). Union by size.
  void Union(int a, int b);

 private:
  std::vector<int> parent_;
  std::vector<std::vector<int>> frames_;  // per root: the sorted frames of its nodes
};

}  // namespace sfm

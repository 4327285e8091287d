#include "frontend/tracks/frame_union_find.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

TEST(FrameUnionFindTest, JoinsNodesOfDifferentFrames) {
  FrameUnionFind sets({0, 1, 2, 3});
  sets.Union(0, 1);
  sets.Union(2, 3);
  EXPECT_EQ(sets.Find(0), sets.Find(1));
  EXPECT_NE(sets.Find(1), sets.Find(2));
  sets.Union(1, 3);
  for (int node = 1; node < 4; ++node) EXPECT_EQ(sets.Find(node), sets.Find(0));
}

TEST(FrameUnionFindTest, RefusesToPutTwoNodesOfOneFrameTogether) {
  // Nodes 0 and 2 are both in frame 5.
  FrameUnionFind sets({5, 6, 5});
  sets.Union(0, 1);
  EXPECT_FALSE(sets.CanUnion(1, 2));
  EXPECT_FALSE(sets.CanUnion(2, 0));
  EXPECT_TRUE(sets.CanUnion(0, 1));  // one component already: a no-op is always allowed
  EXPECT_NE(sets.Find(2), sets.Find(0));
}

}  // namespace
}  // namespace sfm

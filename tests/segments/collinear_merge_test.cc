#include "frontend/segments/collinear_merge.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

// A piece of points every pixel from a to b (offset by `wobble` alternately across the line).
LinePiece Piece(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double wobble = 0,
                const Eigen::Vector2d& gradient = Eigen::Vector2d(0, 1)) {
  LinePiece piece;
  const Eigen::Vector2d n = (b - a).normalized(), q(-n.y(), n.x());
  const int steps = static_cast<int>((b - a).norm());
  for (int i = 0; i <= steps; ++i) piece.fit.Add(a + i * n + (i % 2 ? wobble : -wobble) * q);
  piece.first = a;
  piece.last = a + steps * n;
  piece.gradient_sum = gradient * (steps + 1);
  return piece;
}

TEST(CollinearMergeTest, JoinsPiecesAcrossAShortGap) {
  std::vector<LinePiece> pieces = {Piece({10, 20}, {60, 21}, 0.2), Piece({62.5, 21.05}, {120, 22.2}, 0.2),
                                   Piece({122, 22.25}, {150, 22.8}, 0.2)};
  MergeCollinearPieces(3, 1, &pieces);
  int alive = 0;
  for (const LinePiece& p : pieces) {
    if (p.merged_away) continue;
    ++alive;
    EXPECT_EQ(p.fit.count(), 51 + 58 + 29);
    EXPECT_NEAR(std::min(p.first.x(), p.last.x()), 10, 1e-9);
    EXPECT_NEAR(std::max(p.first.x(), p.last.x()), 150, 0.5);
  }
  EXPECT_EQ(alive, 1);
}

TEST(CollinearMergeTest, KeepsApartWhatIsNotOneLine) {
  // Too far apart.
  std::vector<LinePiece> gap = {Piece({10, 20}, {60, 20}), Piece({65, 20}, {120, 20})};
  MergeCollinearPieces(3, 1, &gap);
  EXPECT_FALSE(gap[0].merged_away || gap[1].merged_away);
  // A corner.
  std::vector<LinePiece> corner = {Piece({10, 20}, {60, 20}), Piece({61, 21}, {61, 80})};
  MergeCollinearPieces(3, 1, &corner);
  EXPECT_FALSE(corner[0].merged_away || corner[1].merged_away);
  // Parallel, 2 px apart.
  std::vector<LinePiece> offset = {Piece({10, 20}, {60, 20}), Piece({61, 22}, {120, 22})};
  MergeCollinearPieces(3, 1, &offset);
  EXPECT_FALSE(offset[0].merged_away || offset[1].merged_away);
  // Opposite polarity.
  std::vector<LinePiece> polarity = {Piece({10, 20}, {60, 20}), Piece({61, 20}, {120, 20}, 0, {0, -1})};
  MergeCollinearPieces(3, 1, &polarity);
  EXPECT_FALSE(polarity[0].merged_away || polarity[1].merged_away);
}

}  // namespace
}  // namespace sfm

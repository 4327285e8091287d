#include "frontend/matching/matching_rule.h"

#include <glog/logging.h>

#include <algorithm>
#include <limits>

namespace sfm {
namespace {

// The best and second-best similarity of the candidates of one junction, and which is best.
struct Ranking {
  double best = -std::numeric_limits<double>::infinity();
  double second = -std::numeric_limits<double>::infinity();
  int best_candidate = -1;

  void Add(double similarity, int candidate) {
    if (similarity > best) {
      second = best;
      best = similarity;
      best_candidate = candidate;
    } else if (similarity > second) {
      second = similarity;
    }
  }
  // (38): the candidate is the largest, and ahead of every other by more than tau2. A tie makes
  // the margin 0, which no tau2 >= 0 passes.
  bool Selects(int candidate, double tau2) const { return candidate == best_candidate && best - second > tau2; }
};

}  // namespace

int PartnerSegment(const JunctionMatch& match, int segment_a, int num_a, int num_b) {
  CHECK(segment_a >= 0 && segment_a < num_a);
  if (segment_a == match.missing_a) return -1;
  // Index among a's segments without missing_a, then the shift, then back into b's numbering
  // skipping missing_b.
  const int reduced_a = match.missing_a >= 0 && segment_a > match.missing_a ? segment_a - 1 : segment_a;
  const int k = match.missing_a >= 0 ? num_a - 1 : num_a;
  CHECK_EQ(k, match.missing_b >= 0 ? num_b - 1 : num_b) << "segment counts do not fit the match";
  const int reduced_b = (reduced_a + match.shift) % k;
  return match.missing_b >= 0 && reduced_b >= match.missing_b ? reduced_b + 1 : reduced_b;
}

std::vector<JunctionMatch> SelectMatches(const std::vector<JunctionMatch>& candidates, int num_a, int num_b,
                                         double tau1, double tau2, const AlliedRivals& allied) {
  std::vector<Ranking> rank_a(num_a);
  std::vector<Ranking> rank_b(num_b);
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    const JunctionMatch& candidate = candidates[c];
    CHECK(candidate.index_a >= 0 && candidate.index_a < num_a && candidate.index_b >= 0 && candidate.index_b < num_b);
    if (!(candidate.similarity > tau1)) continue;
    rank_a[candidate.index_a].Add(candidate.similarity, c);
    rank_b[candidate.index_b].Add(candidate.similarity, c);
  }
  if (allied) {
    // The margin of each junction's best candidate against its rivals that are not allied with it.
    std::vector<double> second_a(num_a, -std::numeric_limits<double>::infinity());
    std::vector<double> second_b(num_b, -std::numeric_limits<double>::infinity());
    for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
      const JunctionMatch& candidate = candidates[c];
      if (!(candidate.similarity > tau1)) continue;
      const int best_a = rank_a[candidate.index_a].best_candidate;
      if (best_a != c && !allied(candidates[best_a], candidate)) {
        second_a[candidate.index_a] = std::max(second_a[candidate.index_a], candidate.similarity);
      }
      const int best_b = rank_b[candidate.index_b].best_candidate;
      if (best_b != c && !allied(candidates[best_b], candidate)) {
        second_b[candidate.index_b] = std::max(second_b[candidate.index_b], candidate.similarity);
      }
    }
    for (int i = 0; i < num_a; ++i) rank_a[i].second = second_a[i];
    for (int j = 0; j < num_b; ++j) rank_b[j].second = second_b[j];
  }
  std::vector<JunctionMatch> matches;
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    const JunctionMatch& candidate = candidates[c];
    if (rank_a[candidate.index_a].Selects(c, tau2) && rank_b[candidate.index_b].Selects(c, tau2)) {
      matches.push_back(candidate);
    }
  }
  return matches;
}

}  // namespace sfm

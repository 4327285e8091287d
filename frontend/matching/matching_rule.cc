#include "frontend/matching/matching_rule.h"

#include <limits>

#include <glog/logging.h>

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

std::vector<JunctionMatch> SelectMatches(const std::vector<JunctionMatch>& candidates, int num_a, int num_b,
                                         double tau1, double tau2) {
  std::vector<Ranking> rank_a(num_a);
  std::vector<Ranking> rank_b(num_b);
  for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
    const JunctionMatch& candidate = candidates[c];
    CHECK(candidate.index_a >= 0 && candidate.index_a < num_a && candidate.index_b >= 0 && candidate.index_b < num_b);
    if (!(candidate.similarity > tau1)) continue;
    rank_a[candidate.index_a].Add(candidate.similarity, c);
    rank_b[candidate.index_b].Add(candidate.similarity, c);
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

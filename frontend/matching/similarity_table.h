// A flat P x Q cache of rho (34) per junction pair, filled on first use: the candidate scan (38)
// and the topology traversals of sigma (section 4.2) ask for the same pairs many times.
#pragma once

#include <glog/logging.h>

#include <functional>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "frontend/matching/junction_similarity.h"

namespace sfm {

class SimilarityTable {
 public:
  using Evaluator = std::function<PairSimilarity(int index_a, int index_b)>;

  // values_ is left uninitialised (only known_ is cleared): a pass reads a small share of the
  // P x Q pairs, and constructing every entry cost more than the entries it evaluates.
  SimilarityTable(int num_a, int num_b, Evaluator evaluate)
      : num_a_(num_a),
        num_b_(num_b),
        evaluate_(std::move(evaluate)),
        values_(std::allocator<PairSimilarity>().allocate(static_cast<size_t>(num_a) * num_b)),
        known_(static_cast<size_t>(num_a) * num_b, 0) {}
  ~SimilarityTable() { std::allocator<PairSimilarity>().deallocate(values_, known_.size()); }
  SimilarityTable(const SimilarityTable&) = delete;
  SimilarityTable& operator=(const SimilarityTable&) = delete;

  const PairSimilarity& Get(int index_a, int index_b) {
    DCHECK(index_a >= 0 && index_a < num_a_ && index_b >= 0 && index_b < num_b_);
    const size_t k = static_cast<size_t>(index_a) * num_b_ + index_b;
    if (!known_[k]) {
      new (&values_[k]) PairSimilarity(evaluate_(index_a, index_b));
      known_[k] = 1;
    }
    return values_[k];
  }

  int num_a() const { return num_a_; }
  int num_b() const { return num_b_; }

 private:
  int num_a_;
  int num_b_;
  Evaluator evaluate_;
  static_assert(std::is_trivially_destructible_v<PairSimilarity>, "values_ entries are never destroyed");
  PairSimilarity* values_;  // entry k is constructed once known_[k] is set
  std::vector<char> known_;
};

}  // namespace sfm

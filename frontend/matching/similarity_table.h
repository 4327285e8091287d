// A flat P x Q cache of rho (34) per junction pair, filled on first use: the candidate scan (38)
// and the topology traversals of sigma (section 4.2) ask for the same pairs many times.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include <glog/logging.h>

#include "frontend/matching/junction_similarity.h"

namespace sfm {

class SimilarityTable {
 public:
  using Evaluator = std::function<PairSimilarity(int index_a, int index_b)>;

  SimilarityTable(int num_a, int num_b, Evaluator evaluate)
      : num_a_(num_a), num_b_(num_b), evaluate_(std::move(evaluate)),
        values_(static_cast<size_t>(num_a) * num_b), known_(values_.size(), 0) {}

  const PairSimilarity& Get(int index_a, int index_b) {
    DCHECK(index_a >= 0 && index_a < num_a_ && index_b >= 0 && index_b < num_b_);
    const size_t k = static_cast<size_t>(index_a) * num_b_ + index_b;
    if (!known_[k]) {
      values_[k] = evaluate_(index_a, index_b);
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
  std::vector<PairSimilarity> values_;
  std::vector<char> known_;
};

}  // namespace sfm

// A flat P x Q cache of rho (34) per junction pair, filled on first use: the candidate scan (38)
// and the topology traversals of sigma (section 4.2) ask for the same pairs many times.
#pragma once

#include <glog/logging.h>

#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "frontend/matching/junction_similarity.h"

namespace sfm {

class SimilarityTable {
 public:
  using Evaluator = std::function<PairSimilarity(int index_a, int index_b)>;

  // Only known_ is cleared: a pass reads a small share of the P x Q pairs. The arrays come from a
  // per-thread pool of released tables: on real images (P, Q ~ 1500) a table is tens of
  // megabytes, and a fresh one per pass cost a page fault at the first touch of each page, more
  // than the entries it evaluated.
  SimilarityTable(int num_a, int num_b, Evaluator evaluate)
      : num_a_(num_a), num_b_(num_b), evaluate_(std::move(evaluate)), buffers_(TakeBuffers()) {
    const size_t size = static_cast<size_t>(num_a) * num_b;
    if (buffers_->values.size() < size) buffers_->values.resize(size);
    buffers_->known.assign(size, 0);
  }
  ~SimilarityTable() { FreeBuffers().push_back(std::move(buffers_)); }
  SimilarityTable(const SimilarityTable&) = delete;
  SimilarityTable& operator=(const SimilarityTable&) = delete;

  const PairSimilarity& Get(int index_a, int index_b) {
    DCHECK(index_a >= 0 && index_a < num_a_ && index_b >= 0 && index_b < num_b_);
    const size_t k = static_cast<size_t>(index_a) * num_b_ + index_b;
    if (!buffers_->known[k]) {
      buffers_->values[k] = evaluate_(index_a, index_b);
      buffers_->known[k] = 1;
    }
    return buffers_->values[k];
  }

  int num_a() const { return num_a_; }
  int num_b() const { return num_b_; }

 private:
  struct Buffers {
    std::vector<PairSimilarity> values;  // entry k is valid once known[k] is set
    std::vector<char> known;
  };
  // The released tables' arrays of this thread (tables may nest, so a list).
  static std::vector<std::unique_ptr<Buffers>>& FreeBuffers() {
    thread_local std::vector<std::unique_ptr<Buffers>> free_buffers;
    return free_buffers;
  }
  static std::unique_ptr<Buffers> TakeBuffers() {
    std::vector<std::unique_ptr<Buffers>>& free_buffers = FreeBuffers();
    if (free_buffers.empty()) return std::make_unique<Buffers>();
    std::unique_ptr<Buffers> buffers = std::move(free_buffers.back());
    free_buffers.pop_back();
    return buffers;
  }

  int num_a_;
  int num_b_;
  Evaluator evaluate_;
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace sfm

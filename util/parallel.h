// Data-parallel loops on TBB (Debian's libtbb), and the thread limit of a run. Results do not
// depend on the thread count when each body(i) writes only its own outputs and whatever is summed
// over the items is summed after the loop, in index order.
#pragma once

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace sfm {

// The threads a run uses: `requested`, or every core the process may run on when it is 0.
int ThreadCount(int requested);

// While it lives, at most ThreadCount(requested) threads run the process's parallel loops: TBB's
// and OpenCV's (Debian's OpenCV runs its own on TBB).
class ThreadLimit {
 public:
  explicit ThreadLimit(int requested);
  int threads() const { return threads_; }

 private:
  int threads_;
  tbb::global_control control_;
};

// body(i) for every i in [0, n), in parallel, in no fixed order.
template <typename Body>
void ParallelFor(int n, const Body& body) {
  tbb::parallel_for(0, n, [&body](int i) { body(i); });
}

}  // namespace sfm

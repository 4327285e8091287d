#include "util/parallel.h"

#include <tbb/info.h>

namespace sfm {

int ThreadCount(int requested) { return requested > 0 ? requested : tbb::info::default_concurrency(); }

ThreadLimit::ThreadLimit(int requested)
    : threads_(ThreadCount(requested)),
      control_(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads_)) {}

}  // namespace sfm

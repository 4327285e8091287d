#include "frontend/segments/nfa.h"

#include <cmath>

#include <glog/logging.h>

namespace sfm {

double Log10BinomialTail(int n, int k, double p) {
  CHECK(0 <= k && k <= n) << "k=" << k << " n=" << n;
  CHECK(0 < p && p < 1);
  if (k == 0) return 0;
  // Sum the terms from k upwards relative to the first one; they fall geometrically once past the
  // mean, so the sum stops when a term no longer changes it.
  const double log_first = std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
                           k * std::log(p) + (n - k) * std::log1p(-p);
  const double odds = p / (1 - p);
  double term = 1, sum = 1;
  for (int i = k; i < n; ++i) {
    term *= (n - i) / (i + 1.0) * odds;
    sum += term;
    if (term < sum * 1e-12) break;
  }
  return (log_first + std::log(sum)) / std::log(10.0);
}

double Log10Nfa(int n, int k, double p, int width, int height) {
  return 2 * std::log10(static_cast<double>(width) * height) + Log10BinomialTail(n, k, p);
}

double Log10Nfa(int n, int k, double p, double log10_tests) { return log10_tests + Log10BinomialTail(n, k, p); }

}  // namespace sfm

#include "sequences/generator/random.h"

#include <cmath>

#include <glog/logging.h>

namespace sfm {

double Random::Uniform() {
  // The top 53 bits scaled by 2^-53: every value is a multiple of 2^-53 in [0, 1).
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double Random::Uniform(double low, double high) { return low + (high - low) * Uniform(); }

int Random::UniformInt(int low, int high) {
  CHECK_LE(low, high);
  const std::uint64_t range = static_cast<std::uint64_t>(static_cast<std::int64_t>(high) - low) + 1;
  // Reject the top partial block of the 2^64 outputs so that every value is equally likely.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;
  std::uint64_t value = engine_();
  while (value >= limit) value = engine_();
  return static_cast<int>(static_cast<std::int64_t>(low) + static_cast<std::int64_t>(value % range));
}

double Random::Gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Marsaglia's polar form of Box-Muller: a uniform point in the unit disc instead of an angle,
  // which saves the sine and cosine.
  double u = 0, v = 0, s = 0;
  do {
    u = 2.0 * Uniform() - 1.0;
    v = 2.0 * Uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return u * factor;
}

std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace sfm

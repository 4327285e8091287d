#include "sequences/generator/random.h"

#include <cmath>

#include <glog/logging.h>

namespace sfm {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

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
  const double u1 = 1.0 - Uniform();  // (0, 1]: the logarithm stays finite
  const double u2 = Uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * kPi * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace sfm

// Random: a seeded pseudo-random source whose output is the same bit for bit on every platform.
//
// std::mt19937_64's output is fixed by the C++ standard, but the distributions built on it
// (std::normal_distribution, std::uniform_real_distribution) are not. So the few distributions the
// generator needs are written here on top of the raw 64-bit engine: uniform reals from the top 53
// bits, integers by rejection, Gaussians by Marsaglia's polar form of the Box-Muller transform
// (Box and Muller 1958; Marsaglia and Bray 1964).
#pragma once

#include <cstdint>
#include <random>

namespace sfm {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t NextU64() { return engine_(); }
  // Uniform in [0, 1), 53 random bits.
  double Uniform();
  // Uniform in [low, high).
  double Uniform(double low, double high);
  // Uniform integer in [low, high] (both included), without modulo bias. CHECKs low <= high.
  int UniformInt(int low, int high);
  // True with probability p.
  bool Bernoulli(double p) { return Uniform() < p; }
  // Standard normal N(0, 1) by the polar Box-Muller method; the second value of each pair is kept
  // for the next call.
  double Gaussian();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

// Derives an independent seed for a sub-stream (scene, odometry, noise of frame i, ...) from a
// master seed, with the SplitMix64 finaliser (Steele, Lea and Flood 2014), so that changing one
// part of a sequence does not change the random numbers of the others.
std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t stream);

}  // namespace sfm

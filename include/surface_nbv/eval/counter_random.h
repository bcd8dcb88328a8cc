// Counter-based random numbers: a value is a pure function of (seed, stream,
// counter), so per-point draws repeat exactly whatever the thread count and
// the order points are visited in. SplitMix64 finaliser; not cryptographic.
#pragma once

#include <cstdint>

namespace surface_nbv {

inline uint64_t mixBits(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) with 53 random bits.
inline double counterUniform(uint64_t seed, uint64_t stream, uint64_t counter) {
  const uint64_t h = mixBits(mixBits(mixBits(seed) ^ stream) + counter);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

}  // namespace surface_nbv

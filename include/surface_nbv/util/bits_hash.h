// One hash for keys made of the exact bits of doubles (positions, poses):
// FNV-1a over the 64-bit words, its high bits folded down. The path
// planner's point caches and the frontier builder's kept views key by it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace surface_nbv {

inline size_t hashBits(const uint64_t* bits, size_t n) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ bits[i]) * 1099511628211ull;
  return static_cast<size_t>(h ^ (h >> 29));
}

}  // namespace surface_nbv

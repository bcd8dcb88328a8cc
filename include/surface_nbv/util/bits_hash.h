// Keys made of the exact bits of doubles (positions, poses), so that caches
// keyed by them never merge two values: BitsKey<N> with equality, an order
// (for ordered maps) and hashBits, FNV-1a over the 64-bit words with its high
// bits folded down. The path planner's point caches (N = 3) and the frontier
// builder's kept views (N = 4) key by it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace surface_nbv {

inline size_t hashBits(const uint64_t* bits, size_t n) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ bits[i]) * 1099511628211ull;
  return static_cast<size_t>(h ^ (h >> 29));
}

template <size_t N>
struct BitsKey {
  std::array<uint64_t, N> bits{};
  BitsKey() = default;
  explicit BitsKey(const double* values) { std::memcpy(bits.data(), values, sizeof(bits)); }
  bool operator==(const BitsKey& o) const { return bits == o.bits; }
  bool operator<(const BitsKey& o) const { return bits < o.bits; }
};

template <size_t N>
struct BitsKeyHash {
  size_t operator()(const BitsKey<N>& k) const { return hashBits(k.bits.data(), N); }
};

}  // namespace surface_nbv

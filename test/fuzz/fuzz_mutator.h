// Seeded mutations for the message fuzz tests: hostile numbers (NaN, +-Inf,
// zero, negative, denormal, huge), hostile sizes and byte-level edits of a
// buffer (bit flips, overwrites, truncation, extension). Every choice comes
// from one std::mt19937, so a run repeats exactly for a given seed.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace surface_nbv {
namespace fuzz {

class Mutator {
 public:
  explicit Mutator(uint32_t seed) : rng_(seed) {}

  // Uniform in [0, n), n > 0.
  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
  uint32_t bits32() { return static_cast<uint32_t>(rng_()); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

  double hostileDouble() {
    switch (below(12)) {
      case 0: return std::numeric_limits<double>::quiet_NaN();
      case 1: return std::numeric_limits<double>::infinity();
      case 2: return -std::numeric_limits<double>::infinity();
      case 3: return 0.0;
      case 4: return -0.0;
      case 5: return std::numeric_limits<double>::denorm_min();
      case 6: return std::numeric_limits<double>::max();
      case 7: return -std::numeric_limits<double>::max();
      case 8: return 1e300;
      case 9: return -uniform(0.0, 10.0);
      case 10: return uniform(1e6, 1e12);
      default: return uniform(-5.0, 5.0);
    }
  }

  float hostileFloat() {
    switch (below(10)) {
      case 0: return std::numeric_limits<float>::quiet_NaN();
      case 1: return std::numeric_limits<float>::infinity();
      case 2: return -std::numeric_limits<float>::infinity();
      case 3: return 0.0f;
      case 4: return -0.0f;
      case 5: return std::numeric_limits<float>::denorm_min();
      case 6: return std::numeric_limits<float>::max();
      case 7: return -static_cast<float>(uniform(0.0, 10.0));
      case 8: return static_cast<float>(uniform(1e6, 1e30));
      default: return static_cast<float>(uniform(-5.0, 5.0));
    }
  }

  // A size near `typical` (off by one, halved, doubled), zero, or huge.
  uint32_t hostileSize(uint32_t typical) {
    switch (below(9)) {
      case 0: return 0;
      case 1: return typical + 1;
      case 2: return typical > 0 ? typical - 1 : 0;
      case 3: return typical / 2;
      case 4: return typical * 2;
      case 5: return std::numeric_limits<uint32_t>::max();
      case 6: return std::numeric_limits<uint32_t>::max() / static_cast<uint32_t>(1 + below(8));
      case 7: return 1u << (16 + below(15));
      default: return static_cast<uint32_t>(below(64));
    }
  }

  // One to four byte-level edits of `bytes`.
  void mutateBytes(std::vector<uint8_t>* bytes) {
    const int edits = 1 + below(4);
    for (int e = 0; e < edits; ++e) {
      const size_t n = bytes->size();
      switch (below(6)) {
        case 0:
          if (n > 0) (*bytes)[pick(n)] ^= static_cast<uint8_t>(1u << below(8));
          break;
        case 1:
          if (n > 0) (*bytes)[pick(n)] = static_cast<uint8_t>(bits32());
          break;
        case 2:
          if (n >= 4) {
            const float f = hostileFloat();
            std::memcpy(bytes->data() + pick(n - 3), &f, 4);
          }
          break;
        case 3:
          bytes->resize(n > 0 ? pick(n) : 0);
          break;
        case 4:
          bytes->resize(n + 1 + pick(16), static_cast<uint8_t>(bits32()));
          break;
        default:
          if (n >= 2) std::swap((*bytes)[pick(n)], (*bytes)[pick(n)]);
          break;
      }
    }
  }

  std::mt19937& rng() { return rng_; }

 private:
  size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }

  std::mt19937 rng_;
};

}  // namespace fuzz
}  // namespace surface_nbv

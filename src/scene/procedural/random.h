// Deterministic random numbers for the procedural scenes. The standard library's distributions
// differ between implementations, so scenes draw from this PCG32 (O'Neill 2014, "PCG: A Family
// of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number Generation")
// and get the same geometry on every platform.
#pragma once
#include <cstdint>

namespace bounce::procedural {

class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed, uint64_t stream = 0x5851f42d4c957f2dull)
      : increment_((stream << 1u) | 1u) {
    nextUint();
    state_ += seed;
    nextUint();
  }

  uint32_t nextUint() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    uint32_t xorShifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rotation = uint32_t(old >> 59u);
    return (xorShifted >> rotation) | (xorShifted << ((32u - rotation) & 31u));
  }

  // Uniform in [0, 1): the top 24 bits fit a float mantissa exactly.
  float uniform() { return float(nextUint() >> 8) * (1.0f / 16777216.0f); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi].
  int uniformInt(int lo, int hi) { return lo + int(nextUint() % uint32_t(hi - lo + 1)); }

 private:
  uint64_t state_ = 0;
  uint64_t increment_;
};

}  // namespace bounce::procedural

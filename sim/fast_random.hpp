#pragma once

#include <cstdint>
#include <limits>

namespace isg::sim {

// SplitMix64's finaliser: a bijective mix of 64 bits, used to derive independent seeds from
// (seed, stream, index) tuples and to fill a generator's state from one word.
constexpr std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A seed for draw `index` of `stream` under `seed`: distinct tuples give unrelated seeds.
constexpr std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return splitMix64(splitMix64(splitMix64(seed) ^ stream) ^ index);
}

// xoshiro256++ (Blackman and Vigna, 2019): 256 bits of state, four shifts and rotations per
// 64-bit draw; several times cheaper than std::mt19937_64, whose 2.5 KB state also makes seeding
// one generator per block of rays expensive. A UniformRandomBitGenerator, so the standard and
// Boost distributions take it.
class Xoshiro256 {
 public:
  using result_type = std::uint64_t;

  explicit Xoshiro256(std::uint64_t seed) {
    for (int i = 0; i < 4; ++i) state_[i] = splitMix64(seed + std::uint64_t(i));
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  result_type operator()() {
    const std::uint64_t out = rotl(state_[0] + state_[3], 23) + state_[0];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return out;
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform01() { return double((*this)() >> 11) * 0x1.0p-53; }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

}  // namespace isg::sim

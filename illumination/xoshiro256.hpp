#pragma once
// xoshiro256** (Blackman and Vigna, "Scrambled linear pseudorandom number generators", 2021),
// seeded through SplitMix64 as its authors recommend: statistically as good as std::mt19937_64
// for Monte Carlo estimates, and seeded in nanoseconds rather than the microseconds
// mt19937_64's 312-word state takes, which would otherwise dominate a 16-sample estimate.

#include <cstdint>

namespace daylit {

class Xoshiro256 {
 public:
  explicit Xoshiro256(std::uint64_t seed) noexcept {
    for (auto& word : s_) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      word = z ^ (z >> 31);
    }
  }
  std::uint64_t operator()() noexcept {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9, t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1), 53 random bits.
  double uniform() noexcept { return double((*this)() >> 11) * 0x1p-53; }
  // Uniform in [lo, hi) (lo < hi): the same numbers on every platform, unlike
  // std::uniform_real_distribution, whose algorithm each standard library chooses.
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi] (lo ≤ hi), without modulo bias: Lemire's multiply-and-reject
  // ("Fast random integer generation in an interval", ACM TOMACS 2019), for the same reason.
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi) noexcept {
    const std::uint64_t range = std::uint64_t(hi) - std::uint64_t(lo) + 1;
    if (range == 0) return std::int64_t((*this)());  // the whole 64-bit range
    unsigned __int128 m = (unsigned __int128)(*this)() * range;
    if (std::uint64_t(m) < range) {
      const std::uint64_t threshold = (0 - range) % range;
      while (std::uint64_t(m) < threshold) m = (unsigned __int128)(*this)() * range;
    }
    return lo + std::int64_t(m >> 64);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace daylit

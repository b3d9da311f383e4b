#pragma once
// SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014; reference code by S. Vigna,
// https://prng.di.unimi.it/splitmix64.c). Our own generator rather than
// <random>: the engines of <random> are specified, but the distributions
// (std::uniform_real_distribution, ...) are implementation-defined, so the
// same seed would give different track profiles with different standard
// libraries. Everything here is unsigned 64-bit integer arithmetic (exact and
// wrapping on every machine) plus one exact conversion to double.
#include <cstdint>

namespace railvsi {

class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}

  constexpr std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  // Uniform on [0, 1): the top 53 bits times 2^-53. Both steps are exact in
  // IEEE 754 double, so the value is the same on every machine.
  constexpr double next_unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace railvsi

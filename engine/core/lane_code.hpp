#pragma once
// Which machine code runs a computation compiled twice, for the baseline
// processor and for one with AVX2: the fastest this processor has, or the
// portable one. Both give the same bits (no FMA); tests compare them.
namespace railvsi {

enum class LaneCode { kFastest, kPortable };

// True when `code` may use AVX2 here (the processor's features are read once).
inline bool use_avx2(LaneCode code) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2 && code == LaneCode::kFastest;
}

}  // namespace railvsi

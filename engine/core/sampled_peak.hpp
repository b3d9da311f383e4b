#pragma once
// The peak of a signal known at equally spaced samples. The largest sample
// misses a peak that falls between two samples: for a harmonic sampled n
// times a period it is low by up to 1 - cos(pi / n). Through the largest
// sample of each local maximum of |s| and its two neighbours passes one
// parabola, whose vertex estimates the peak between them; for a harmonic
// it is low by at most 1 - cos(pi / n) (1 + sin^2(pi / n) / 2), reached
// when the peak lies half a step from a sample (0.85 % at n = 8 against
// 7.6 % for the largest sample alone).
#include <cstddef>

#include "core/lane_code.hpp"

namespace railvsi {

// max |s[i * stride]| over n samples, each local maximum of |s| raised to
// the vertex of the parabola through it and its neighbours' |s| (never
// below the samples themselves). The same bits whatever the stride and in
// reverse order. NaN when a sample is NaN. 0 for n = 0.
// `code`: contiguous samples go four at a time, in AVX2 where the processor
// has it (kFastest) or in the baseline code (kPortable): the same bits.
double refined_max_abs(const double* s, std::size_t n, std::size_t stride = 1, LaneCode code = LaneCode::kFastest);
// The same when the largest |sample| is known (the producer of the samples
// kept it): max_abs_sample raised to the vertices above it. NaN stays NaN.
double refine_max_abs(const double* s, std::size_t n, std::size_t stride, double max_abs_sample,
                      LaneCode code = LaneCode::kFastest);

// How low the largest sample of a harmonic sampled n times a period can be
// (relative): 1 - cos(pi / n).
double sampled_peak_error(double samples_per_period);
// How low refined_max_abs of a harmonic sampled n times a period can be
// (relative): 1 - cos(pi / n) (1 + sin^2(pi / n) / 2).
double refined_peak_error(double samples_per_period);

}  // namespace railvsi

#pragma once
// The low-pass filter of deck accelerations required by EN 1990 A2.4.4.2.1:
// peak deck accelerations are assessed "considering frequencies up to"
// f_cut = max(30 Hz, 1.5 f0, f3). The code names no filter. In the modal
// practice the code was written for, modes above f_cut are left out and
// modes below it count in full, so the filter here approximates that
// truncation from the safe side:
//
//   * Butterworth low-pass with 8 poles, from the analog prototype by the
//     bilinear transform with pre-warping (so the digital response equals
//     the analog one at the pre-warped frequency), as 4 second-order
//     sections with unit DC gain;
//   * applied forward and backward (zero phase: a peak is not shifted in
//     time and the two passes square the magnitude), so that
//       |H(f)| = 1 / (1 + (tan(pi f dt) / tan(pi f_c dt))^16);
//   * f_c placed so that |H(f_cut)| = 0.99: a mode at the code frequency
//     keeps 99 % of its amplitude (the attenuation is of the order of the
//     time step's own sampling error), |H| = 0.5 at f_c ~ 1.333 f_cut,
//     0.13 at 1.5 f_cut and 0.0015 at 2 f_cut.
//   * edges: the signal is extended at both ends by its odd reflection
//     (value and slope continuous) over the time the slowest pole needs to
//     decay to 1e-8, and each pass starts from the steady state of its first
//     input sample, so a constant passes unchanged and no start-up transient
//     reaches the signal.
//
// A plain forward-backward Butterworth with f_c = f_cut (gain 0.5 at the
// code frequency) would halve a mode at f3 when f3 sets f_cut. An FFT brick
// wall truncates exactly at f_cut but rings (Gibbs) across the whole record;
// this filter's impulse response decays exponentially.
#include "core/lane_code.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace railvsi {

inline constexpr int kCodeFilterPoles = 8;                 // per pass
inline constexpr double kCodeFilterGainAtCutoff = 0.99;     // both passes

// max(30 Hz, 1.5 f0, f3). Pass 0 for a frequency that is not known.
double code_cutoff_hz(double f0_hz, double f3_hz);

// f_c of the design: where the two passes together have gain 0.5.
// Requires 0 < cutoff_hz < 0.5 / dt_s.
double code_filter_half_gain_hz(double dt_s, double cutoff_hz);

// The filtered signal, same length. dt_s > 0 and cutoff_hz > 0 (else
// std::invalid_argument). When cutoff_hz is at or above the Nyquist
// frequency 0.5/dt_s nothing sampled lies above it: the signal comes back
// unchanged. Deterministic: the same input gives the same bits.
std::vector<double> code_low_pass(const std::vector<double>& signal, double dt_s, double cutoff_hz);

// The filter of one (dt, cut-off), designed once and applied to many
// signals without allocating (the workspace grows to the longest signal):
// max_abs_filtered(x) == refined_max_abs(code_low_pass(x)) bit for bit:
// the largest |value|, each local maximum raised to its parabola's vertex
// (core/sampled_peak.hpp), so a peak between two samples is not missed.
class CodeFilter {
 public:
  CodeFilter(double dt_s, double cutoff_hz);
  double max_abs_filtered(const std::vector<double>& signal, std::vector<double>& workspace) const;
  // The same for up to kLanes signals at once, their passes run side by
  // side (independent recursions the processor overlaps): maxima[i] ==
  // max_abs_filtered(*signals[i]) bit for bit.
  static constexpr int kLanes = 4;
  // The signals padded and the forward pass's output, kLanes doubles per
  // sample, and one lane's filtered samples (sized on first use).
  struct LaneWorkspace {
    std::vector<double> padded, reversed, lane;
  };
  void max_abs_filtered(const std::vector<const std::vector<double>*>& signals, double* maxima, LaneWorkspace& ws,
                        LaneCode code = LaneCode::kFastest) const;

 private:
  friend std::vector<double> code_low_pass(const std::vector<double>&, double, double);
  // The padded, filtered signal in workspace; returns the padding.
  std::size_t filter_into(const std::vector<double>& signal, std::vector<double>& x) const;
  // The padding of a signal of n >= 2 samples at each end.
  std::size_t padding(std::size_t n) const;
  // The signal with `pad` samples reflected at each end, into x[i * stride].
  void pad_into(const std::vector<double>& signal, std::size_t pad, double* x, std::size_t stride) const;
  bool pass_through_ = false;  // cut-off at or above Nyquist
  double b_[4][3] = {}, a_[4][2] = {};
  std::size_t pad_ = 0;        // before clamping to the signal length
};

// "Butterworth 8 poles forward-backward, gain 0.99 at 30.0 Hz, 0.5 at 40.0 Hz"
std::string code_filter_description(double dt_s, double cutoff_hz);

}  // namespace railvsi

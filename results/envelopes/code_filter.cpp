#include "envelopes/code_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;

// One second-order section, direct form II transposed, a0 = 1.
struct Section {
  double b0, b1, b2, a1, a2;
};

using Sections = std::array<Section, kCodeFilterPoles / 2>;

// Analog Butterworth pole pair k has damping sin(pi (2k+1) / (2n)); with
// K = tan(pi f_c dt) (pre-warped, s normalized by 2/dt) the bilinear
// transform of K^2 / (s^2 + 2 zeta K s + K^2) is the section below. Its DC
// gain is exactly 1: (b0 + b1 + b2) = 4K^2/a0 = 1 + a1 + a2.
Sections design(double dt_s, double half_gain_hz) {
  const double K = std::tan(kPi * half_gain_hz * dt_s);
  Sections s{};
  for (int k = 0; k < kCodeFilterPoles / 2; ++k) {
    const double zeta = std::sin(kPi * (2 * k + 1) / (2.0 * kCodeFilterPoles));
    const double a0 = 1.0 + 2.0 * zeta * K + K * K;
    const double b0 = K * K / a0;
    s[static_cast<std::size_t>(k)] = {b0, 2.0 * b0, b0, 2.0 * (K * K - 1.0) / a0, (1.0 - 2.0 * zeta * K + K * K) / a0};
  }
  return s;
}

void check_arguments(double dt_s, double cutoff_hz) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw std::invalid_argument("code filter: dt_s must be > 0");
  if (!(cutoff_hz > 0.0) || !std::isfinite(cutoff_hz))
    throw std::invalid_argument("code filter: cutoff_hz must be > 0");
}

}  // namespace

double code_cutoff_hz(double f0_hz, double f3_hz) { return std::max({30.0, 1.5 * f0_hz, f3_hz}); }

double code_filter_half_gain_hz(double dt_s, double cutoff_hz) {
  check_arguments(dt_s, cutoff_hz);
  if (cutoff_hz * dt_s >= 0.5) throw std::invalid_argument("code filter: cut-off at or above the Nyquist frequency");
  // Both passes: |H(f)| = 1 / (1 + r^(2n)), r = tan(pi f dt) / tan(pi f_c dt).
  // |H(f_cut)| = g gives r = (1/g - 1)^(1/(2n)) at f_cut.
  const double r = std::pow(1.0 / kCodeFilterGainAtCutoff - 1.0, 1.0 / (2.0 * kCodeFilterPoles));
  return std::atan(std::tan(kPi * cutoff_hz * dt_s) / r) / (kPi * dt_s);
}

namespace {

// One causal pass (direct form II transposed, a0 = 1) through the four
// sections, forward (step +1) or backward (-1) over x, in place. Each
// section starts from the steady state of a constant input equal to the
// pass's first sample (each has unit DC gain, so every section sees x0 at
// steady state): y = x0 needs z2 = (b2 - a2) x0 and z1 = (b1 + b2 - a1 - a2) x0.
// The sections run interleaved sample by sample: each sees the same inputs
// in the same order as when they run one after the other, but the four
// recursions overlap in the processor instead of waiting for each other.
template <int kStep>
void fused_pass(const double (&b)[4][3], const double (&a)[4][2], std::vector<double>& x) {
  if (x.empty()) return;
  const std::size_t n = x.size();
  double* v = kStep > 0 ? x.data() : x.data() + n - 1;
  const double x0 = *v;
  double z1[4], z2[4];
  for (int k = 0; k < 4; ++k) {
    z1[k] = (b[k][1] + b[k][2] - a[k][0] - a[k][1]) * x0;
    z2[k] = (b[k][2] - a[k][1]) * x0;
  }
  for (std::size_t i = 0; i < n; ++i, v += kStep) {
    double in = *v;
    for (int k = 0; k < 4; ++k) {
      const double out = b[k][0] * in + z1[k];
      z1[k] = b[k][1] * in - a[k][0] * out + z2[k];
      z2[k] = b[k][2] * in - a[k][1] * out;
      in = out;
    }
    *v = in;
  }
}

// fused_pass over up to four signals side by side, one per lane of a
// vector of four doubles: lane l runs over x[l] (n[l] samples; idle lanes
// have none) with the arithmetic of fused_pass, element by element (the
// same products and sums in the same order, so the same bits). A lane that
// has ended is fed zeros, which it never stores.
constexpr int kL = CodeFilter::kLanes;
static_assert(kL == 4, "four doubles per vector");
using Lanes = double __attribute__((vector_size(4 * sizeof(double))));

template <int kStep>
[[gnu::always_inline]] inline void fused_pass_lanes(const double (&b)[4][3], const double (&a)[4][2],
                                                    const std::array<double*, kL>& x,
                                                    const std::array<std::size_t, kL>& n) {
  Lanes b0[4], a1[4], a2[4], z1[4], z2[4];
  std::size_t longest = 0;
  std::array<double*, kL> v{};
  Lanes x0;
  for (int l = 0; l < kL; ++l) {
    longest = std::max(longest, n[static_cast<std::size_t>(l)]);
    const std::size_t nl = n[static_cast<std::size_t>(l)];
    double* xl = x[static_cast<std::size_t>(l)];
    v[static_cast<std::size_t>(l)] = nl == 0 ? nullptr : kStep > 0 ? xl : xl + nl - 1;
    x0[l] = nl == 0 ? 0.0 : *v[static_cast<std::size_t>(l)];
  }
  for (int k = 0; k < 4; ++k) {
    // A scalar in a vector expression stands for all four lanes.
    b0[k] = Lanes{} + b[k][0];
    a1[k] = Lanes{} + a[k][0];
    a2[k] = Lanes{} + a[k][1];
    z1[k] = (b[k][1] + b[k][2] - a[k][0] - a[k][1]) * x0;
    z2[k] = (b[k][2] - a[k][1]) * x0;
  }
  // The four sections on one sample of every lane, in place. A low-pass
  // section has b1 = 2 b0 and b2 = b0 exactly (see design()), so b1 in and
  // b2 in are t + t and t for t = b0 in, the same bits in fewer products.
  const auto section_cascade = [&](Lanes& in) {
    for (int k = 0; k < 4; ++k) {
      const Lanes t = b0[k] * in;
      const Lanes out = t + z1[k];
      z1[k] = (t + t) - a1[k] * out + z2[k];
      z2[k] = t - a2[k] * out;
      in = out;
    }
  };
  // While every lane has samples: loaded and stored as they are.
  std::size_t shortest = longest;
  for (int l = 0; l < kL; ++l) shortest = std::min(shortest, n[static_cast<std::size_t>(l)]);
  for (std::size_t i = 0; i < shortest; ++i) {
    Lanes out{*v[0], *v[1], *v[2], *v[3]};
    section_cascade(out);
    *v[0] = out[0];
    *v[1] = out[1];
    *v[2] = out[2];
    *v[3] = out[3];
    for (int l = 0; l < kL; ++l) v[static_cast<std::size_t>(l)] += kStep;
  }
  // The longer lanes' last samples.
  for (std::size_t i = shortest; i < longest; ++i) {
    Lanes in{};
    for (int l = 0; l < kL; ++l) in[l] = i < n[static_cast<std::size_t>(l)] ? *v[static_cast<std::size_t>(l)] : 0.0;
    section_cascade(in);
    const Lanes& out = in;
    for (int l = 0; l < kL; ++l) {
      if (i >= n[static_cast<std::size_t>(l)]) continue;
      *v[static_cast<std::size_t>(l)] = out[l];
      v[static_cast<std::size_t>(l)] += kStep;
    }
  }
}

// Both passes, compiled twice: for the baseline processor and with AVX2
// (four doubles per instruction; no FMA, so the bits do not change).
void forward_backward_lanes(const double (&b)[4][3], const double (&a)[4][2], const std::array<double*, kL>& x,
                            const std::array<std::size_t, kL>& n) {
  fused_pass_lanes<1>(b, a, x, n);
  fused_pass_lanes<-1>(b, a, x, n);
}
[[gnu::target("avx2")]] void forward_backward_lanes_avx2(const double (&b)[4][3], const double (&a)[4][2],
                                                         const std::array<double*, kL>& x,
                                                         const std::array<std::size_t, kL>& n) {
  fused_pass_lanes<1>(b, a, x, n);
  fused_pass_lanes<-1>(b, a, x, n);
}

// max |y| over y[first, first + n); NaN propagates: a non-finite input is
// never hidden by the maximum.
double max_abs(const double* y, std::size_t n) {
  double m = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = y[i];
    m = std::isnan(v) || std::isnan(m) ? std::nan("") : std::max(m, std::abs(v));
  }
  return m;
}

}  // namespace

CodeFilter::CodeFilter(double dt_s, double cutoff_hz) {
  check_arguments(dt_s, cutoff_hz);
  static_assert(kCodeFilterPoles == 8, "the fused pass has four sections");
  if (cutoff_hz * dt_s >= 0.5) {
    pass_through_ = true;
    return;
  }
  const double fc = code_filter_half_gain_hz(dt_s, cutoff_hz);
  const Sections sections = design(dt_s, fc);
  for (std::size_t k = 0; k < sections.size(); ++k) {
    // The lanes' pass counts on it (b1 = 2 b0 is exact: a power of two).
    if (sections[k].b1 != 2.0 * sections[k].b0 || sections[k].b2 != sections[k].b0)
      throw std::logic_error("code filter: a low-pass section has b = b0 (1, 2, 1)");
    b_[k][0] = sections[k].b0;
    b_[k][1] = sections[k].b1;
    b_[k][2] = sections[k].b2;
    a_[k][0] = sections[k].a1;
    a_[k][1] = sections[k].a2;
  }
  // The slowest pole (damping sin(pi/2n)) decays to 1e-8 in ln(1e8) / (zeta
  // 2 pi f_c): pad that long, or as long as the signal allows.
  const double zeta_min = std::sin(kPi / (2.0 * kCodeFilterPoles));
  const double pad_s = std::log(1e8) / (zeta_min * 2.0 * kPi * fc);
  pad_ = static_cast<std::size_t>(std::ceil(pad_s / dt_s));
}

std::size_t CodeFilter::pad_into(const std::vector<double>& signal, std::vector<double>& x) const {
  const std::size_t n = signal.size();
  const std::size_t pad = std::min(n - 1, pad_);
  // Odd reflection about each end: x(-k) = 2 x(0) - x(k).
  x.resize(n + 2 * pad);
  for (std::size_t k = 0; k < pad; ++k) x[k] = 2.0 * signal.front() - signal[pad - k];
  std::copy(signal.begin(), signal.end(), x.begin() + static_cast<std::ptrdiff_t>(pad));
  for (std::size_t k = 1; k <= pad; ++k) x[pad + n - 1 + k] = 2.0 * signal.back() - signal[n - 1 - k];
  return pad;
}

std::size_t CodeFilter::filter_into(const std::vector<double>& signal, std::vector<double>& x) const {
  const std::size_t pad = pad_into(signal, x);
  fused_pass<1>(b_, a_, x);
  fused_pass<-1>(b_, a_, x);  // backward: zero phase
  return pad;
}

double CodeFilter::max_abs_filtered(const std::vector<double>& signal, std::vector<double>& workspace) const {
  const std::size_t n = signal.size();
  std::size_t first = 0;
  const std::vector<double>* y = &signal;
  if (n >= 2 && !pass_through_) {
    first = filter_into(signal, workspace);
    y = &workspace;
  }
  return max_abs(y->data() + first, n);
}

void CodeFilter::max_abs_filtered(const std::vector<const std::vector<double>*>& signals, double* maxima,
                                  std::array<std::vector<double>, kLanes>& workspaces) const {
  if (signals.size() > static_cast<std::size_t>(kLanes))
    throw std::invalid_argument("code filter: more signals than lanes");
  std::array<double*, kLanes> x{};
  std::array<std::size_t, kLanes> length{}, first{};
  for (std::size_t l = 0; l < signals.size(); ++l) {
    const std::vector<double>& signal = *signals[l];
    if (signal.size() < 2 || pass_through_) continue;  // as max_abs_filtered: the signal itself
    first[l] = pad_into(signal, workspaces[l]);
    x[l] = workspaces[l].data();
    length[l] = workspaces[l].size();
  }
  // Backward: zero phase. The processor's features are read once.
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) forward_backward_lanes_avx2(b_, a_, x, length);
  else forward_backward_lanes(b_, a_, x, length);
  for (std::size_t l = 0; l < signals.size(); ++l) {
    const std::vector<double>& signal = *signals[l];
    maxima[l] = length[l] == 0 ? max_abs(signal.data(), signal.size())
                               : max_abs(workspaces[l].data() + first[l], signal.size());
  }
}

std::vector<double> code_low_pass(const std::vector<double>& signal, double dt_s, double cutoff_hz) {
  const CodeFilter filter(dt_s, cutoff_hz);
  const std::size_t n = signal.size();
  if (n < 2 || filter.pass_through_) return signal;
  std::vector<double> x;
  const std::size_t pad = filter.filter_into(signal, x);
  return {x.begin() + static_cast<std::ptrdiff_t>(pad), x.begin() + static_cast<std::ptrdiff_t>(pad + n)};
}

std::string code_filter_description(double dt_s, double cutoff_hz) {
  check_arguments(dt_s, cutoff_hz);
  if (cutoff_hz * dt_s >= 0.5)
    return fmt::format("none: cut-off {:.1f} Hz at or above the Nyquist frequency {:.1f} Hz", cutoff_hz,
                       0.5 / dt_s);
  return fmt::format("Butterworth {} poles forward-backward, gain {} at {:.1f} Hz, 0.5 at {:.1f} Hz",
                     kCodeFilterPoles, kCodeFilterGainAtCutoff, cutoff_hz, code_filter_half_gain_hz(dt_s, cutoff_hz));
}

}  // namespace railvsi

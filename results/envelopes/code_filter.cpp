#include "envelopes/code_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "core/sampled_peak.hpp"

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
// A low-pass section has b = b0 (1, 2, 1) (checked when the filter is
// made): b1 in and b2 in are evaluated as t + t and t for t = b0 in, here
// and in the lanes below, so that both give the same bits for every input
// (2 (b0 in) and (2 b0) in differ when b0 in is subnormal).
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
      const double t = b[k][0] * in;
      const double out = t + z1[k];
      z1[k] = (t + t) - a[k][0] * out + z2[k];
      z2[k] = t - a[k][1] * out;
      in = out;
    }
    *v = in;
  }
}

// fused_pass over up to four signals side by side, one per lane of a
// vector of four doubles, with the arithmetic of fused_pass element by
// element (the same products and sums in the same order: the same bits).
// The signals are interleaved (kL doubles per sample, one vector load per
// sample): four separate arrays, a multiple of 4 KiB apart, made the
// processor wait on false store-to-load dependencies, and each sample took
// four scalar loads and stores. The forward pass writes each lane's output
// reversed into `reversed`, so that the backward pass runs forward over it
// (every lane from its own last sample) and only takes the maximum.
constexpr int kL = CodeFilter::kLanes;
static_assert(kL == 4, "four doubles per vector");
using Lanes = double __attribute__((vector_size(4 * sizeof(double))));
// The same, read in place in a buffer of doubles (no alignment beyond a double's).
using LanesInBuffer = double __attribute__((vector_size(4 * sizeof(double)), aligned(alignof(double)), may_alias));

// One lane's signal: n samples, padded by `pad` at each end to `length`
// (0 for an idle lane or one that is not filtered).
struct LanePlan {
  std::size_t n = 0, pad = 0, length = 0;
};

struct LaneCascade {
  Lanes b0[4], a1[4], a2[4], z1[4], z2[4];
  // Each section starts from the steady state of a constant input x0 (see fused_pass).
  LaneCascade(const double (&b)[4][3], const double (&a)[4][2], const Lanes& x0) {
    for (int k = 0; k < 4; ++k) {
      // A scalar in a vector expression stands for all four lanes.
      b0[k] = Lanes{} + b[k][0];
      a1[k] = Lanes{} + a[k][0];
      a2[k] = Lanes{} + a[k][1];
      z1[k] = (b[k][1] + b[k][2] - a[k][0] - a[k][1]) * x0;
      z2[k] = (b[k][2] - a[k][1]) * x0;
    }
  }
  // The four sections on one sample of every lane, in place, with the
  // arithmetic of fused_pass (b1 in and b2 in as t + t and t).
  [[gnu::always_inline]] void operator()(Lanes& in) {
    for (int k = 0; k < 4; ++k) {
      const Lanes t = b0[k] * in;
      const Lanes out = t + z1[k];
      z1[k] = (t + t) - a1[k] * out + z2[k];
      z2[k] = t - a2[k] * out;
      in = out;
    }
  }
};

// Both passes over the interleaved padded signals (`longest` samples;
// what a lane has past its length is never read back). The backward pass
// leaves its output in `reversed`, sample j of every lane at j kL: lane l's
// own samples (its padding excluded) are j in [pad, pad + n), in reverse
// time order; maxima[l] = max |y| over them, NaN when one of them is NaN.
[[gnu::always_inline]] inline void forward_backward(const double (&b)[4][3], const double (&a)[4][2],
                                                    const std::array<LanePlan, kL>& plan, std::size_t longest,
                                                    const double* padded, double* reversed,
                                                    std::array<double, kL>& maxima) {
  // Sample i of every lane, in place (a pointer: no vector crosses a call).
  const auto at = [](const double* buffer, std::size_t i) {
    return reinterpret_cast<const LanesInBuffer*>(buffer + i * kL);
  };
  {
    const Lanes first = *at(padded, 0);  // copied: a Lanes reference assumes a vector's alignment
    LaneCascade cascade(b, a, first);
    // Lane l's output i goes to reversed[(length - 1 - i) kL + l]. While
    // every lane has samples the four go out unconditionally, each lane
    // straight from the register (a lane that is not filtered writes as if
    // its length were the longest: it is never read).
    std::array<double*, kL> to{};
    std::size_t shortest = longest;
    for (std::size_t l = 0; l < kL; ++l) {
      const std::size_t length = plan[l].length > 0 ? plan[l].length : longest;
      shortest = std::min(shortest, length);
      to[l] = reversed + (length - 1) * kL + l;
    }
    std::size_t i = 0;
    for (; i < shortest; ++i) {
      Lanes y = *at(padded, i);
      cascade(y);
      *to[0] = y[0];
      *to[1] = y[1];
      *to[2] = y[2];
      *to[3] = y[3];
      for (double*& t : to) t -= kL;
    }
    for (; i < longest; ++i) {
      Lanes y = *at(padded, i);
      cascade(y);
      for (std::size_t l = 0; l < kL; ++l)
        if (i < plan[l].length) reversed[(plan[l].length - 1 - i) * kL + l] = y[l];
    }
  }
  // Samples where every filtered lane is inside its own signal: one vector maximum.
  std::size_t all_from = 0, all_to = longest;
  for (const LanePlan& p : plan)
    if (p.length > 0) {
      all_from = std::max(all_from, p.pad);
      all_to = std::min(all_to, p.pad + p.n);
    }
  Lanes m{}, nan{};
  const Lanes last = *at(reversed, 0);
  LaneCascade cascade(b, a, last);
  for (std::size_t j = 0; j < longest; ++j) {
    auto* sample = reinterpret_cast<LanesInBuffer*>(reversed + j * kL);
    Lanes y = *sample;
    cascade(y);
    *sample = y;
    if (j >= all_from && j < all_to) {
      const Lanes ay = y < 0.0 ? -y : y;  // |-0.0| = -0.0 here, which the maximum never keeps over 0.0
      m = m < ay ? ay : m;
      nan = y != y ? Lanes{} + 1.0 : nan;
      continue;
    }
    for (std::size_t l = 0; l < kL; ++l) {
      if (j < plan[l].pad || j >= plan[l].pad + plan[l].n) continue;
      m[l] = std::max(m[l], std::abs(y[l]));
      if (std::isnan(y[l])) nan[l] = 1.0;
    }
  }
  for (std::size_t l = 0; l < kL; ++l) maxima[l] = nan[l] != 0.0 ? std::nan("") : m[l];
}

// Compiled twice: for the baseline processor and with AVX2 (four doubles
// per instruction; no FMA, so the bits do not change).
void forward_backward_baseline(const double (&b)[4][3], const double (&a)[4][2], const std::array<LanePlan, kL>& plan,
                               std::size_t longest, const double* padded, double* reversed,
                               std::array<double, kL>& maxima) {
  forward_backward(b, a, plan, longest, padded, reversed, maxima);
}
[[gnu::target("avx2")]] void forward_backward_avx2(const double (&b)[4][3], const double (&a)[4][2],
                                                   const std::array<LanePlan, kL>& plan, std::size_t longest,
                                                   const double* padded, double* reversed,
                                                   std::array<double, kL>& maxima) {
  forward_backward(b, a, plan, longest, padded, reversed, maxima);
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
    // The passes count on it (they evaluate b1 in and b2 in from b0 in).
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

std::size_t CodeFilter::padding(std::size_t n) const { return std::min(n - 1, pad_); }

void CodeFilter::pad_into(const std::vector<double>& signal, std::size_t pad, double* x, std::size_t stride) const {
  const std::size_t n = signal.size();
  // Odd reflection about each end: x(-k) = 2 x(0) - x(k).
  for (std::size_t k = 0; k < pad; ++k) x[k * stride] = 2.0 * signal.front() - signal[pad - k];
  for (std::size_t k = 0; k < n; ++k) x[(pad + k) * stride] = signal[k];
  for (std::size_t k = 1; k <= pad; ++k) x[(pad + n - 1 + k) * stride] = 2.0 * signal.back() - signal[n - 1 - k];
}

std::size_t CodeFilter::filter_into(const std::vector<double>& signal, std::vector<double>& x) const {
  const std::size_t pad = padding(signal.size());
  x.resize(signal.size() + 2 * pad);
  pad_into(signal, pad, x.data(), 1);
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
  return refined_max_abs(y->data() + first, n);
}

void CodeFilter::max_abs_filtered(const std::vector<const std::vector<double>*>& signals, double* maxima,
                                  LaneWorkspace& ws, LaneCode code) const {
  if (signals.size() > static_cast<std::size_t>(kLanes))
    throw std::invalid_argument("code filter: more signals than lanes");
  std::array<LanePlan, kLanes> plan{};
  std::size_t longest = 0;
  for (std::size_t l = 0; l < signals.size(); ++l) {
    const std::size_t n = signals[l]->size();
    if (n < 2 || pass_through_) continue;  // as max_abs_filtered: the signal itself
    const std::size_t pad = padding(n);
    plan[l] = {n, pad, n + 2 * pad};
    longest = std::max(longest, plan[l].length);
  }
  std::array<double, kLanes> sampled{};
  if (longest > 0) {
    // Each lane's padded signal (pad_into), interleaved. What a
    // lane has past its own length (left by an earlier call) only ever
    // reaches samples nobody reads, so the buffers are not cleared (that
    // was half the filter's time); a lane not filtered gets zeros.
    ws.padded.resize(longest * kLanes);
    ws.reversed.resize(longest * kLanes);
    for (std::size_t l = 0; l < kLanes; ++l) {
      const LanePlan& p = plan[l];
      if (p.length == 0) {
        for (std::size_t i = 0; i < longest; ++i) ws.padded[i * kLanes + l] = 0.0;
        continue;
      }
      pad_into(*signals[l], p.pad, ws.padded.data() + l, kLanes);
    }
    if (use_avx2(code)) forward_backward_avx2(b_, a_, plan, longest, ws.padded.data(), ws.reversed.data(), sampled);
    else forward_backward_baseline(b_, a_, plan, longest, ws.padded.data(), ws.reversed.data(), sampled);
  }
  // The same samples as max_abs_filtered's, in reverse order: the same
  // maximum. Each lane's samples side by side first (the refinement looks
  // at contiguous samples four at a time).
  for (std::size_t l = 0; l < signals.size(); ++l) {
    if (plan[l].length == 0) {
      maxima[l] = refined_max_abs(signals[l]->data(), signals[l]->size(), 1, code);
      continue;
    }
    ws.lane.resize(plan[l].n);
    const double* from = ws.reversed.data() + plan[l].pad * kLanes + l;
    for (std::size_t i = 0; i < plan[l].n; ++i) ws.lane[i] = from[i * kLanes];
    maxima[l] = refine_max_abs(ws.lane.data(), plan[l].n, 1, sampled[l], code);
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

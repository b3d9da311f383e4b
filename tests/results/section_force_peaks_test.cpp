// The section forces' peaks of the modal sweep between its samples: at the
// deck's sampling step (the refined rule, 8 samples a period of the code
// frequency for a 1 % tolerance) against the same sweep at a step 16 times
// shorter, over the HSLM-A trains and their speeds on the standard 15 m
// span (S2) and on a short stiff span. A form's influence line has a kink
// (a jump for a shear cut) where an axle stands on its section or support;
// the sweep evaluates the forms there (ModalSweep's kinks), so a peak at a
// kink is not missed between two samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/modal_sweep.hpp"
#include "generators/bridge_2d.hpp"
#include "generators/hslm.hpp"
#include "planning/effects_planner.hpp"
#include "simulation/modal_section_forces.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

struct HslmRow {
  int N;
  double D_m, d_m, P_kN;
};
// EN 1991-2 Table E.4.
constexpr HslmRow kHslmA[] = {{18, 18, 2.0, 170}, {17, 19, 3.5, 200}, {16, 20, 2.0, 180}, {15, 21, 3.0, 190},
                              {14, 22, 2.0, 170}, {13, 23, 2.0, 180}, {13, 24, 2.0, 190}, {12, 25, 2.5, 190},
                              {11, 26, 2.0, 210}, {11, 27, 2.0, 210}};

// The section peaks of one run: midspan moment and shear, then per support
// its reaction and end rotation.
std::vector<double> peaks_of(const ModalSweepRun& run) {
  RunSummary s;
  s.points.resize(1);
  run.sections->summarize(s);
  std::vector<double> v{*s.points[0].max_abs_bending_moment_Nm, *s.points[0].max_abs_shear_force_N};
  for (const SupportSummary& sup : s.supports) {
    v.push_back(sup.max_reaction_N);
    v.push_back(sup.max_abs_rotation_rad);
  }
  return v;
}

// The reference's step: dt / 16 (its own error, a peak at a kink exact and
// a smooth one sampled 128 times a period of the code frequency, 0.03 %).
constexpr double kFiner = 16.0;

struct Errors {
  std::vector<double> worst;  // per quantity, the largest relative difference over trains and speeds
};

// Every HSLM-A train at speeds 100..400 km/h (step speed_step_kmh) on a
// span of span_m with first frequency f0_hz: the peaks at dt against dt / kFiner.
Errors sweep_errors(double span_m, double f0_hz, double mass_kg_per_m, double speed_step_kmh) {
  Bridge2dOptions b;
  b.spans_m = {span_m};
  b.deck_first_frequency_hz = f0_hz;
  b.deck_mass_kg_per_m = mass_kg_per_m;
  b.damping_ratio = 0.01;
  b.output_points = {{"midspan", 0.5 * span_m}};
  const auto structure = make_bridge_2d(b);
  // The planner's modes and step for this deck (f3 = 9 f0 for a simple span).
  const double code_hz = std::max({30.0, 1.5 * f0_hz, 9.0 * f0_hz});
  ModalBasisOptions o;
  o.max_frequency_hz = kModalCutoffMargin * code_hz;
  const ModalBasis basis(structure, o);
  const auto sections = modal_section_forces(basis, {0});
  const double dt = modal_time_step_s(code_hz, 0.01, ModalPeaks::kRefinedWithSections);
  Errors e;
  ModalSweepWorkspace ws;
  for (const HslmRow& r : kHslmA) {
    const Train train = make_hslm_a({r.N, r.D_m, r.d_m, r.P_kN * 1e3}, "HSLM-A");
    const ModalSweep c(basis, train, {0}, dt, sections), f(basis, train, {0}, dt / kFiner, sections);
    const double length_m = train.moving_forces.back().offset_m + span_m;
    for (double kmh = 100.0; kmh <= 400.0 + 1e-9; kmh += speed_step_kmh) {
      const double v = kmh / 3.6;
      const auto steps = [&](double h) { return static_cast<long>(std::ceil(length_m / v / h)); };
      const ModalSweepRun rc = c.run(0.0, v, steps(dt), ws);
      const ModalSweepRun rf = f.run(0.0, v, steps(dt / kFiner), ws);
      const std::vector<double> pc = peaks_of(rc), pf = peaks_of(rf);
      e.worst.resize(pc.size(), 0.0);
      for (std::size_t i = 0; i < pc.size(); ++i)
        e.worst[i] = testing::worst_of(e.worst[i], std::abs(pc[i] - pf[i]) / pf[i]);
    }
  }
  return e;
}

void print(const char* name, const Errors& e) {
  std::printf("[section peaks] %s, refined at the deck's step against dt/16: M %.3f %%, V %.3f %%, reactions %.3f %% "
              "%.3f %%, end rotations %.3f %% %.3f %%\n",
              name, 100 * e.worst[0], 100 * e.worst[1], 100 * e.worst[2], 100 * e.worst[4], 100 * e.worst[3],
              100 * e.worst[5]);
}

// Per quantity (moment, shear, reactions 1 and 2, end rotations 1 and 2):
// the largest relative difference allowed, 3 x the one measured or the
// planner's 1 % tolerance, whichever is smaller.
void expect_within(const Errors& e, const std::vector<double>& bound) {
  ASSERT_EQ(e.worst.size(), bound.size());
  for (std::size_t i = 0; i < bound.size(); ++i) EXPECT_LE(e.worst[i], bound[i]) << "quantity " << i;
}

TEST(SectionForcePeaks, AtTheDecksStepTheyAreWithinTheToleranceOfAStep16TimesShorterOnS2) {
  // S2: 15 m, 5 Hz, 15 t/m, 1 %; 3 modes to 54 Hz, dt 2.77 ms (8 samples
  // a period of 45 Hz); 10 trains x 61 speeds.
  const Errors e = sweep_errors(15.0, 5.0, 15000.0, 5.0);
  print("15 m, 5 Hz", e);
  // Measured 2026-11-27: M 0.167 %, V 0.817 %, R 0.303 % 0.366 %, theta
  // 0.156 % 0.145 % (the largest sample alone, before: M 0.40 %, V 7.9 %,
  // R 4.8 % 5.0 %, theta 0.17 % 0.15 %).
  expect_within(e, {0.005, 0.01, 0.009, 0.0047, 0.01, 0.0044});
}

TEST(SectionForcePeaks, AtTheDecksStepTheyAreWithinTheToleranceOfAStep16TimesShorterOnAShortSpan) {
  // A short stiff span: 8 m, 12 Hz (EN 1991-2 Figure 6.10's upper limit is
  // 94.76 L^-0.748 = 19.7 Hz), 10 t/m; f3 = 108 Hz, dt 1.15 ms; 10 trains
  // x 31 speeds.
  const Errors e = sweep_errors(8.0, 12.0, 10000.0, 10.0);
  print("8 m, 12 Hz", e);
  // Measured 2026-11-27: M 0.246 %, V 0.631 %, R 0.349 % 0.524 %, theta
  // 0.120 % 0.120 % (the largest sample alone, before: M 0.41 %, V 10.4 %,
  // R 4.9 % 4.4 %, theta 0.22 % 0.21 %).
  expect_within(e, {0.0074, 0.01, 0.01, 0.0036, 0.01, 0.0036});
}

}  // namespace
}  // namespace railvsi

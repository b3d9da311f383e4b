// Is the planner safe? For HSLM sweeps (A1 to A10 x 101 speeds, 100-400 km/h)
// on a 15 m and a 25 m simply supported span, the planner's answer (the
// modal moving-force rung at its sampling step, through the job path:
// ModalSweep, CodeFilter, envelopes) against the full model for a load
// model (moving forces on the FE structure, HHT, the time-step policy's dt
// / 4): every governing envelope value (per train, the largest over the
// speeds of the filtered deck acceleration and the deck displacement at
// midspan), relative difference and the CPU time of both.
// Then the same for a 3D deck (deck-3d: three 25 m spans of hexahedra, two
// rails on pads, each axle shared between them), every train at its
// resonance speed f0 x coach length and 4 % either side, the largest over
// the three midspans; RAILVSI_SAFETY_3D_DOFS sets its size (default 6,000;
// 0 leaves the case out).
// Run by hand: OPENBLAS_NUM_THREADS=1 build/tests/bench/planner_safety_bench [speed step km/h, default 3 | 3d]
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <string>

#include "analysis/modal_moving_forces.hpp"
#include "cpu_time.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/job_envelopes.hpp"
#include "generators/bridge_2d.hpp"
#include "generators/deck_3d.hpp"
#include "io/train_loader.hpp"
#include "planning/effects_planner.hpp"
#include "planning/time_step_policy.hpp"
#include "simulation/simulation.hpp"
#include "study/deck_frequencies.hpp"
#include "study/scene_plan.hpp"

namespace {

using namespace railvsi;

double cpu_s() { return bench::thread_cpu_s(); }

struct Span {
  const char* name;
  double length_m, f0_hz;
};

void compare(const Span& span, int step_kmh) {
  Bridge2dOptions b;
  b.spans_m = {span.length_m};
  b.deck_first_frequency_hz = span.f0_hz;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.01;
  b.output_points = {{"midspan", span.length_m / 2}};
  const auto structure = make_bridge_2d(b);
  const scheduler::DeckFrequencies f = scheduler::deck_frequencies(*structure);
  const double code_hz = code_cutoff_hz(f.f0_hz, f.f3_hz);
  PlannerInput in;
  in.f0_hz = f.f0_hz;
  in.f3_hz = f.f3_hz;
  in.modes_below_cutoff = scheduler::count_modes(structure, kModalCutoffMargin * code_hz);
  const EffectsPlan plan = plan_effects(in);
  // Deck peaks alone (no section forces, one rail line): refined between samples.
  const double dt_modal = modal_time_step_s(plan.code_frequency_hz, in.tolerance, ModalPeaks::kRefined);
  ModalBasisOptions mo;
  mo.max_frequency_hz = plan.modal_cutoff_hz;
  const double t_basis = cpu_s();
  const ModalBasis basis(structure, mo);
  double planner_s = cpu_s() - t_basis, full_s = 0.0;
  const CodeFilter filter(dt_modal, code_hz);
  std::printf("%s: f0 %.2f Hz, f3 %.2f Hz, code frequency %.1f Hz; planner: %s, %d modes to %.1f Hz, dt %.3g s\n",
              span.name, f.f0_hz, f.f3_hz, code_hz, plan.rung.name().c_str(), basis.num_modes(), plan.modal_cutoff_hz,
              dt_modal);
  double worst_acc = 0.0, worst_disp = 0.0, gov_acc_p = 0.0, gov_acc_f = 0.0, gov_disp_p = 0.0, gov_disp_f = 0.0;
  double dt_full = 0.0;
  for (int a = 1; a <= 10; ++a) {
    Scene s;
    s.structure = structure;
    s.train = load_library_train("HSLM-A" + std::to_string(a));
    double acc_p = 0.0, acc_f = 0.0, disp_p = 0.0, disp_f = 0.0;
    const double t0 = cpu_s();
    s.analysis.dt_s = dt_modal;
    const ModalSweep sweep(basis, s.train, s.analysis.contact.rail_lines, dt_modal);
    ModalSweepWorkspace ws;
    std::vector<double> fws;
    for (int v = 100; v <= 400; v += step_kmh) {
      s.speed_mps = v / 3.6;
      const ModalSweepRun run = sweep.run(modal_run_start_x_m(s), s.speed_mps, modal_run_steps(s), ws);
      acc_p = std::max(acc_p, filter.max_abs_filtered(ws.acceleration[0][0], fws));
      disp_p = std::max(disp_p, run.max_abs_displacement_m[0]);
    }
    planner_s += cpu_s() - t0;
    const double t1 = cpu_s();
    for (int v = 100; v <= 400; v += step_kmh) {
      s.speed_mps = v / 3.6;
      TimeStepPolicy policy;
      const TimeStepChoice c =
          choose_time_step(*structure, s.train, s.speed_mps, s.analysis.contact, f.f0_hz, f.f3_hz, policy);
      s.analysis.dt_s = c.dt_s / 4.0;
      dt_full = s.analysis.dt_s;
      const Result r = Simulation(s).run();
      const JobEnvelopes e = compute_envelopes(r, s.analysis.dt_s, 1, code_hz);
      acc_f = std::max(acc_f, e.max_abs_acceleration_mps2.value_or(NAN));
      disp_f = std::max(disp_f, e.max_abs_displacement_m.value_or(NAN));
    }
    full_s += cpu_s() - t1;
    const double ea = acc_p / acc_f - 1.0, ed = disp_p / disp_f - 1.0;
    worst_acc = std::max(worst_acc, std::abs(ea));
    worst_disp = std::max(worst_disp, std::abs(ed));
    gov_acc_p = std::max(gov_acc_p, acc_p);
    gov_acc_f = std::max(gov_acc_f, acc_f);
    gov_disp_p = std::max(gov_disp_p, disp_p);
    gov_disp_f = std::max(gov_disp_f, disp_f);
    std::printf("  HSLM-A%-2d acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%)\n", a, acc_p, acc_f,
                100 * ea, disp_p, disp_f, 100 * ed);
  }
  std::printf("  governing: acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%); worst per train acc "
              "%.3f %%, disp %.3f %%; full model dt %.3g s; CPU planner %.2f s vs full %.2f s (%.0fx)\n",
              gov_acc_p, gov_acc_f, 100 * (gov_acc_p / gov_acc_f - 1), gov_disp_p, gov_disp_f,
              100 * (gov_disp_p / gov_disp_f - 1), 100 * worst_acc, 100 * worst_disp, dt_full, planner_s, full_s,
              full_s / planner_s);
}

// The 3D deck: the planner's answer at the job path's step (two rail lines
// keep the largest sample, for the deck twist) against FE at the policy's
// dt / 4, per train the largest over its speeds and the three midspans.
void compare_3d(int dofs) {
  Deck3dOptions d;
  d.target_dofs = dofs;
  d.approach_m = 30.0;  // moving forces need no track to stand on before the bridge
  const Deck3d deck = make_deck_3d(d);
  const auto structure = deck.model;
  const std::vector<int> rails{0, 1};
  const double t_plan = cpu_s();
  const scheduler::DeckFrequencies f = scheduler::deck_frequencies(*structure);
  const double code_hz = code_cutoff_hz(f.f0_hz, f.f3_hz);
  PlannerInput in;
  in.f0_hz = f.f0_hz;
  in.f3_hz = f.f3_hz;
  in.modes_below_cutoff = scheduler::count_modes(structure, kModalCutoffMargin * code_hz, f.lowest_hz);
  const EffectsPlan plan = plan_effects(in);
  if (!plan.rung.exact_modal()) {
    std::printf("3D deck, %d DOFs: the planner chose %s, not the modal rung\n", structure->num_dofs(),
                plan.rung.name().c_str());
    return;
  }
  const double dt_modal = modal_time_step_s(plan.code_frequency_hz, in.tolerance, ModalPeaks::kSampled);
  ModalBasisOptions mo;
  mo.max_frequency_hz = plan.modal_cutoff_hz;
  const ModalBasis basis(structure, mo);
  double planner_s = cpu_s() - t_plan, full_s = 0.0;
  const CodeFilter filter(dt_modal, code_hz);
  const std::size_t np = structure->outputs().size();
  std::printf("3D deck, %d DOFs (frequencies and count %.1f s CPU): f0 %.2f Hz, f3 %.2f Hz, code frequency %.1f Hz; "
              "planner: %s, %d modes to %.1f Hz, dt %.3g s\n",
              structure->num_dofs(), planner_s, f.f0_hz, f.f3_hz, code_hz, plan.rung.name().c_str(), basis.num_modes(),
              plan.modal_cutoff_hz, dt_modal);
  double worst_acc = 0.0, worst_disp = 0.0, gov_acc_p = 0.0, gov_acc_f = 0.0, gov_disp_p = 0.0, gov_disp_f = 0.0;
  for (int a = 1; a <= 10; ++a) {
    Scene s;
    s.structure = structure;
    s.train = load_library_train("HSLM-A" + std::to_string(a));
    s.analysis.contact.rail_lines = rails;
    const double resonance_mps = f.f0_hz * s.train.coach_length_m;
    double acc_p = 0.0, acc_f = 0.0, disp_p = 0.0, disp_f = 0.0;
    const double t0 = cpu_s();
    s.analysis.dt_s = dt_modal;
    const ModalSweep sweep(basis, s.train, rails, dt_modal);
    ModalSweepWorkspace ws;
    std::vector<double> fws;
    for (double factor : {0.96, 1.0, 1.04}) {
      s.speed_mps = factor * resonance_mps;
      const ModalSweepRun run = sweep.run(modal_run_start_x_m(s), s.speed_mps, modal_run_steps(s), ws);
      for (std::size_t i = 0; i < np; ++i) {
        acc_p = std::max(acc_p, filter.max_abs_filtered(ws.acceleration[0][i], fws));
        disp_p = std::max(disp_p, run.max_abs_displacement_m[i]);
      }
    }
    planner_s += cpu_s() - t0;
    const double t1 = cpu_s();
    double dt_full = 0.0;
    for (double factor : {0.96, 1.0, 1.04}) {
      s.speed_mps = factor * resonance_mps;
      TimeStepPolicy policy;
      const TimeStepChoice c =
          choose_time_step(*structure, s.train, s.speed_mps, s.analysis.contact, f.f0_hz, f.f3_hz, policy);
      s.analysis.dt_s = c.dt_s / 4.0;
      dt_full = s.analysis.dt_s;
      const Result r = Simulation(s).run();
      const JobEnvelopes e = compute_envelopes(r, s.analysis.dt_s, 1, code_hz);
      acc_f = std::max(acc_f, e.max_abs_acceleration_mps2.value_or(NAN));
      disp_f = std::max(disp_f, e.max_abs_displacement_m.value_or(NAN));
    }
    full_s += cpu_s() - t1;
    const double ea = acc_p / acc_f - 1.0, ed = disp_p / disp_f - 1.0;
    worst_acc = std::max(worst_acc, std::abs(ea));
    worst_disp = std::max(worst_disp, std::abs(ed));
    gov_acc_p = std::max(gov_acc_p, acc_p);
    gov_acc_f = std::max(gov_acc_f, acc_f);
    gov_disp_p = std::max(gov_disp_p, disp_p);
    gov_disp_f = std::max(gov_disp_f, disp_f);
    std::printf("  HSLM-A%-2d at %.0f km/h +-4 %%: acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%); "
                "full model dt %.3g s\n",
                a, 3.6 * resonance_mps, acc_p, acc_f, 100 * ea, disp_p, disp_f, 100 * ed, dt_full);
    std::fflush(stdout);
  }
  std::printf("  governing: acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%); worst per train acc "
              "%.3f %%, disp %.3f %%; CPU planner %.2f s vs full %.2f s (%.0fx)\n",
              gov_acc_p, gov_acc_f, 100 * (gov_acc_p / gov_acc_f - 1), gov_disp_p, gov_disp_f,
              100 * (gov_disp_p / gov_disp_f - 1), 100 * worst_acc, 100 * worst_disp, planner_s, full_s,
              full_s / planner_s);
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // "3d": the 3D deck alone.
  const bool only_3d = argc > 1 && std::string(argv[1]) == "3d";
  const int step_kmh = argc > 1 && !only_3d ? std::max(1, std::atoi(argv[1])) : 3;
  if (!only_3d) {
    compare({"15 m span", 15.0, 5.0}, step_kmh);
    compare({"25 m span", 25.0, 5.69}, step_kmh);  // the hslm-sweep example's deck
  }
  const char* dofs_3d = std::getenv("RAILVSI_SAFETY_3D_DOFS");
  const int dofs = dofs_3d ? std::atoi(dofs_3d) : 6000;
  if (dofs > 0) compare_3d(dofs);
  return 0;
}

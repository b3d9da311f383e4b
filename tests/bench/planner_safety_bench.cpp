// Is the planner safe? For HSLM sweeps (A1 to A10 x 101 speeds, 100-400 km/h)
// on a 15 m and a 25 m simply supported span, the planner's answer (the
// modal moving-force rung at its sampling step, through the job path:
// ModalSweep, CodeFilter, envelopes) against the full model for a load
// model (moving forces on the FE structure, HHT, the time-step policy's dt
// / 4): every governing envelope value (per train, the largest over the
// speeds of the filtered deck acceleration and the deck displacement at
// midspan), relative difference and the CPU time of both (the planner's
// from the deck frequencies on: its count, modes and runs).
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
#include <functional>
#include <string>
#include <vector>

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
#include "planning/deck_frequencies.hpp"
#include "planning/scene_plan.hpp"
#include "../support/worst_of.hpp"

namespace {

using namespace railvsi;

double cpu_s() { return bench::thread_cpu_s(); }

struct Case {
  std::string name;
  std::shared_ptr<const StructureModel> structure;
  std::vector<int> rail_lines{0};
  // Deck peaks alone on one rail line are refined between samples; two
  // rail lines keep the largest sample (the job path's step, for the deck
  // twist).
  ModalPeaks peaks = ModalPeaks::kRefined;
  // The speeds (m/s) each train runs at, from the deck's f0.
  std::function<std::vector<double>(const Train&, double f0_hz)> speeds_mps;
  std::string speeds_text;  // what the speeds are, for the output
};

struct Peaks {
  double acc = 0.0, disp = 0.0;  // filtered acceleration, displacement: largest over speeds and points
};

// Per train, the largest filtered deck acceleration and displacement over
// its speeds and the output points: the planner's answer (the modal sweep
// of the job path) against FE at the policy's dt / 4.
void compare(const Case& c) {
  const auto& structure = c.structure;
  const double t_plan = cpu_s();
  const DeckFrequencies f = deck_frequencies(*structure);
  const double code_hz = code_cutoff_hz(f.f0_hz, f.f3_hz);
  PlannerInput in;
  in.f0_hz = f.f0_hz;
  in.f3_hz = f.f3_hz;
  in.modes_below_cutoff = count_modes(structure, kModalCutoffMargin * code_hz, f.lowest_hz);
  const EffectsPlan plan = plan_effects(in);
  if (!plan.rung.exact_modal()) {
    std::printf("%s, %d DOFs: the planner chose %s, not the modal rung\n", c.name.c_str(), structure->num_dofs(),
                plan.rung.name().c_str());
    return;
  }
  const double dt_modal = modal_time_step_s(plan.code_frequency_hz, in.tolerance, c.peaks);
  ModalBasisOptions mo;
  mo.max_frequency_hz = plan.modal_cutoff_hz;
  const ModalBasis basis(structure, mo);
  double planner_s = cpu_s() - t_plan, full_s = 0.0;
  const CodeFilter filter(dt_modal, code_hz);
  const std::size_t np = structure->outputs().size();
  std::printf("%s, %d DOFs: f0 %.2f Hz, f3 %.2f Hz, code frequency %.1f Hz; planner: %s, %d modes to %.1f Hz, dt %.3g "
              "s (frequencies, count and modes %.2f s CPU); speeds: %s\n",
              c.name.c_str(), structure->num_dofs(), f.f0_hz, f.f3_hz, code_hz, plan.rung.name().c_str(),
              basis.num_modes(), plan.modal_cutoff_hz, dt_modal, planner_s, c.speeds_text.c_str());
  double worst_acc = 0.0, worst_disp = 0.0, dt_full = 0.0;
  Peaks governing_p, governing_f;
  for (int a = 1; a <= 10; ++a) {
    Scene s;
    s.structure = structure;
    s.train = load_library_train("HSLM-A" + std::to_string(a));
    s.analysis.contact.rail_lines = c.rail_lines;
    const std::vector<double> speeds = c.speeds_mps(s.train, f.f0_hz);
    Peaks p, full;
    const double t0 = cpu_s();
    s.analysis.dt_s = dt_modal;
    const ModalSweep sweep(basis, s.train, c.rail_lines, dt_modal);
    ModalSweepWorkspace ws;
    std::vector<double> fws;
    for (double v : speeds) {
      s.speed_mps = v;
      const ModalSweepRun run = sweep.run(modal_run_start_x_m(s), s.speed_mps, modal_run_steps(s), ws);
      for (std::size_t i = 0; i < np; ++i) {
        p.acc = railvsi::testing::worst_of(p.acc, filter.max_abs_filtered(ws.acceleration[0][i], fws));
        p.disp = railvsi::testing::worst_of(p.disp, run.max_abs_displacement_m[i]);
      }
    }
    planner_s += cpu_s() - t0;
    const double t1 = cpu_s();
    for (double v : speeds) {
      s.speed_mps = v;
      TimeStepPolicy policy;
      const TimeStepChoice choice =
          choose_time_step(*structure, s.train, s.speed_mps, s.analysis.contact, f.f0_hz, f.f3_hz, policy);
      s.analysis.dt_s = choice.dt_s / 4.0;
      dt_full = s.analysis.dt_s;
      const Result r = Simulation(s).run();
      const JobEnvelopes e = compute_envelopes(r, s.analysis.dt_s, 1, code_hz);
      full.acc = railvsi::testing::worst_of(full.acc, e.max_abs_acceleration_mps2.value_or(NAN));
      full.disp = railvsi::testing::worst_of(full.disp, e.max_abs_displacement_m.value_or(NAN));
    }
    full_s += cpu_s() - t1;
    const double ea = p.acc / full.acc - 1.0, ed = p.disp / full.disp - 1.0;
    worst_acc = railvsi::testing::worst_of(worst_acc, std::abs(ea));
    worst_disp = railvsi::testing::worst_of(worst_disp, std::abs(ed));
    governing_p = {std::max(governing_p.acc, p.acc), std::max(governing_p.disp, p.disp)};
    governing_f = {std::max(governing_f.acc, full.acc), std::max(governing_f.disp, full.disp)};
    std::printf("  HSLM-A%-2d acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%)\n", a, p.acc, full.acc,
                100 * ea, p.disp, full.disp, 100 * ed);
  }
  std::printf("  governing: acc %.4f vs %.4f m/s2 (%+.3f %%), disp %.4e vs %.4e m (%+.3f %%); worst per train acc "
              "%.3f %%, disp %.3f %%; full model dt %.3g s; CPU planner %.2f s vs full %.2f s (%.0fx)\n",
              governing_p.acc, governing_f.acc, 100 * (governing_p.acc / governing_f.acc - 1), governing_p.disp,
              governing_f.disp, 100 * (governing_p.disp / governing_f.disp - 1), 100 * worst_acc, 100 * worst_disp,
              dt_full, planner_s, full_s, full_s / planner_s);
}

// A simply supported span of 15 t/m, 1 %, every train at step_kmh from
// 100 to 400 km/h, output at midspan.
Case span_case(const char* name, double length_m, double f0_hz, int step_kmh) {
  Bridge2dOptions b;
  b.spans_m = {length_m};
  b.deck_first_frequency_hz = f0_hz;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.01;
  b.output_points = {{"midspan", length_m / 2}};
  Case c;
  c.name = name;
  c.structure = make_bridge_2d(b);
  c.speeds_mps = [step_kmh](const Train&, double) {
    std::vector<double> v;
    for (int kmh = 100; kmh <= 400; kmh += step_kmh) v.push_back(kmh / 3.6);
    return v;
  };
  c.speeds_text = "100-400 km/h every " + std::to_string(step_kmh) + " km/h";
  return c;
}

// The 3D deck, each axle shared between its two rails, every train at its
// resonance speed f0 x coach length and 4 % either side.
Case deck_3d_case(int dofs) {
  Deck3dOptions d;
  d.target_dofs = dofs;
  d.approach_m = 30.0;  // moving forces need no track to stand on before the bridge
  Case c;
  c.name = "3D deck";
  c.structure = make_deck_3d(d).model;
  c.rail_lines = {0, 1};
  c.peaks = ModalPeaks::kSampled;
  c.speeds_mps = [](const Train& train, double f0_hz) {
    const double resonance_mps = f0_hz * train.coach_length_m;
    return std::vector<double>{0.96 * resonance_mps, resonance_mps, 1.04 * resonance_mps};
  };
  c.speeds_text = "f0 x coach length and 4 % either side";
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // "3d": the 3D deck alone.
  const bool only_3d = argc > 1 && std::string(argv[1]) == "3d";
  const int step_kmh = argc > 1 && !only_3d ? std::max(1, std::atoi(argv[1])) : 3;
  if (!only_3d) {
    compare(span_case("15 m span", 15.0, 5.0, step_kmh));
    compare(span_case("25 m span", 25.0, 5.69, step_kmh));  // the hslm-sweep example's deck
  }
  const char* dofs_3d = std::getenv("RAILVSI_SAFETY_3D_DOFS");
  const int dofs = dofs_3d ? std::atoi(dofs_3d) : 6000;
  if (dofs > 0) compare(deck_3d_case(dofs));
  return 0;
}

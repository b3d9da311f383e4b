// Seed-scale benchmark (the paper's example at its size;
// docs/performance.md "Seed scale"): a generated 3D deck of 233,292 DOFs (the paper's count),
// the 46-axle KHST of the train library at 120 m/s, dt = 2.5e-4 s, 2,000
// steps, HHT alpha = -0.05, nonlinear Hertz, each wheelset on both rails.
// It takes tens of minutes and a few GB: run by hand, never in CI:
//   OPENBLAS_NUM_THREADS=1 build/tests/bench/seed_scale_bench
// (RAILVSI_SEED_DOFS=50000 builds a smaller deck of the same kind, to try
// changes; the numbers in docs/performance.md are at the full size.)
// Times are also given as a ratio to a floor measured in the same process,
// one structure solve with the cached factor:
//   overhead = (wall - setup) / (steps x t_solve)
// (the floor is 1.0 when the operator splits its solve at the rails,
// solver/rail_suffix.hpp, 2.0 otherwise).
// The same scene on the modal interaction rung, for each mode count (or
// cut-off, "60hz") listed in RAILVSI_SEED_MODES:
//   RAILVSI_SEED_MODES=10,20,25,40 OPENBLAS_NUM_THREADS=1 build/tests/bench/seed_scale_bench
// runs the FE scene first (the reference) and then one modal run per entry,
// each timed by component (modes, operator, statics, loop) and compared with
// the FE run: max deck displacement, max deck acceleration filtered as EN
// 1990 A2.4.4.2.1 asks (results/envelopes/code_filter.hpp) and unfiltered
// (relative errors), max wheel unloading dQ/Q (absolute error). The
// filter's cut-off is the code's floor, 30 Hz, as in the first tables of
// docs/performance.md (`vsi simulate` takes f3 = 36.3 Hz for this deck since it
// computes deck frequencies up to 300,000 DOFs); RAILVSI_SEED_CUTOFF_HZ
// sets another.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/huge_pages.hpp"
#include "core/input_error.hpp"
#include "envelopes/code_filter.hpp"
#include "generators/deck_3d.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "solve_floor.hpp"
#include "solver/cholmod_operator.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

// Peak resident memory since the last reset (VmHWM of /proc/self/status;
// writing 5 to /proc/self/clear_refs resets it to the current RSS, Linux
// proc(5)), so each component reports its own peak.
double component_peak_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return 0.0;
}
void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }


using bench::cpu_seconds;

// Wall and CPU seconds and peak memory of one component; printed as soon as
// it ends, so that a run stopped early still tells what it measured.
struct Component {
  double wall_s = 0.0, cpu_s = 0.0, peak_mb = 0.0;
};
template <class F>
Component measure(const char* name, F&& f) {
  reset_peak();
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  f();
  Component c{seconds_since(t0), cpu_seconds() - c0, component_peak_mb()};
  std::fprintf(stderr, "[seed] %-10s wall %8.2f s  cpu %8.2f s  peak %7.0f MB\n", name, c.wall_s, c.cpu_s,
               c.peak_mb);
  return c;
}

// The scene of the benchmark on a structure generated once per process
// (the FE and modal runs share it).
Scene seed_scene(Component* generate) {
  static std::shared_ptr<const StructureModel> structure;
  if (!structure) {
    Deck3dOptions o;
    o.target_dofs = 233292;
    // A smaller model of the same kind for trying changes (not the benchmark).
    if (const char* dofs = std::getenv("RAILVSI_SEED_DOFS")) o.target_dofs = std::atoi(dofs);
    const Component c = measure("generate", [&] { structure = make_deck_3d(o).model; });
    if (generate) *generate = c;
  }
  Scene scene;
  scene.structure = structure;
  scene.train = load_library_train("KHST");
  scene.speed_mps = 120.0;
  scene.analysis.dt_s = 2.5e-4;
  scene.analysis.hht = HhtParameters::from_alpha(-0.05);
  scene.analysis.contact.law = "hertz";
  scene.analysis.contact.rail_lines = {0, 1};
  scene.analysis.duration_s = 2000 * 2.5e-4;
  return scene;
}

// The FE run's results, kept for the modal runs' errors.
struct Reference {
  RunSummary summary;
  Histories histories;
};
std::optional<Reference>& fe_reference() {
  static std::optional<Reference> reference;
  return reference;
}

void BM_SeedScaleKhst(benchmark::State& state) {
  Result r;
  Component generate, oper, statics, loop;
  double t_solve = 0.0, t_solve_cpu = 0.0;
  std::shared_ptr<const CholmodOperator> op;
  for (auto _ : state) {
    Scene scene = seed_scene(&generate);
    oper = measure("operator", [&] {
      op = std::dynamic_pointer_cast<const CholmodOperator>(make_structure_operator(scene));
    });
    std::unique_ptr<Simulation> sim;
    statics = measure("statics", [&] { sim = std::make_unique<Simulation>(scene, op); });
    loop = measure("time loop", [&] { r = sim->run(); });
    state.PauseTiming();
    const double c0 = cpu_seconds();
    t_solve = bench::seconds_per_solve(*op, 20);
    t_solve_cpu = (cpu_seconds() - c0) / 20;
    state.ResumeTiming();
  }
  if (r.status.ok()) fe_reference() = Reference{r.summary, r.histories};
  if (!r.status.ok()) state.SkipWithError(r.status.message().c_str());
  const RunSummary& s = r.summary;
  const double steps = static_cast<double>(s.steps), loop_s = s.wall_s - s.setup_s;
  state.counters["dofs"] = s.fidelity.structure_dofs;
  state.counters["vehicle_dofs"] = s.fidelity.vehicle_dofs;
  state.counters["contacts"] = s.fidelity.contacts;
  state.counters["generate_s"] = generate.wall_s;
  state.counters["factorization_s"] = op ? op->factorization_s() : 0.0;
  state.counters["analysis_s"] = op ? op->analysis_s() : 0.0;  // part of factorization_s
  state.counters["flexibility_s"] = op ? op->flexibility_s() : 0.0;
  state.counters["flexibility_solves"] = op ? op->flexibility_solves() : 0.0;
  state.counters["operator_s"] = oper.wall_s;
  state.counters["statics_s"] = statics.wall_s;  // static equilibrium (factor of K with K_bar's ordering)
  state.counters["one_solve_per_step"] = op && op->splits_at_rails() ? 1.0 : 0.0;
  state.counters["suffix_columns"] = op && op->splits_at_rails() ? op->num_dofs() - op->suffix_start() : 0.0;
  state.counters["factor_nnz"] = op ? op->factor_nonzeros() : 0.0;
  state.counters["factor_MB"] = op ? 8.0 * op->factor_nonzeros() / 1e6 : 0.0;  // values only
  state.counters["peak_rss_MB"] = peak_rss_mb();
  state.counters["generate_MB"] = generate.peak_mb;  // peak resident memory during each component
  state.counters["operator_MB"] = oper.peak_mb;
  state.counters["statics_MB"] = statics.peak_mb;
  state.counters["loop_MB"] = loop.peak_mb;
  state.counters["steps"] = steps;
  state.counters["s_per_step"] = loop_s / steps;
  state.counters["newton_per_step"] = static_cast<double>(s.newton_iterations) / steps;
  state.counters["solve_s"] = t_solve;
  state.counters["overhead"] = loop_s / (steps * t_solve);
  // The same ratio in CPU time (the loop's CPU time over the solve's).
  state.counters["solve_cpu_s"] = t_solve_cpu;
  state.counters["overhead_cpu"] = loop.cpu_s / (steps * t_solve_cpu);
  state.counters["cpu_total_s"] = generate.cpu_s + oper.cpu_s + statics.cpu_s + loop.cpu_s;
  state.counters["total_s"] = generate.wall_s + oper.wall_s + statics.wall_s + loop.wall_s;
  state.counters["max_deck_acc"] = s.max_abs_acceleration_mps2;
  state.counters["max_unloading"] = s.max_unloading_ratio;
}
BENCHMARK(BM_SeedScaleKhst)->Unit(benchmark::kSecond)->Iterations(1);

// The largest filtered deck acceleration over the output points.
double max_filtered_acceleration(const Histories& h, double dt_s, double cutoff_hz) {
  const CodeFilter filter(dt_s, cutoff_hz);
  std::vector<double> workspace;
  double peak = 0.0;
  for (const auto& a : h.deck_acceleration_mps2) peak = railvsi::testing::worst_of(peak, filter.max_abs_filtered(a, workspace));
  return peak;
}

// max over points and time of |u - u_ref|, over max |u_ref|: the error of
// the whole displacement history, not only of its peak.
double displacement_history_error(const Histories& h, const Histories& ref) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t p = 0; p < ref.deck_displacement_m.size() && p < h.deck_displacement_m.size(); ++p)
    for (std::size_t k = 0; k < ref.deck_displacement_m[p].size() && k < h.deck_displacement_m[p].size(); ++k) {
      diff = railvsi::testing::worst_of(diff, std::abs(h.deck_displacement_m[p][k] - ref.deck_displacement_m[p][k]));
      peak = railvsi::testing::worst_of(peak, std::abs(ref.deck_displacement_m[p][k]));
    }
  return diff / peak;
}

// One entry of RAILVSI_SEED_MODES: a mode count ("50") or a cut-off ("60hz").
void BM_SeedScaleKhstModal(benchmark::State& state, const std::string& entry) {
  const bool is_cutoff = entry.find_first_of("hH") != std::string::npos;
  Result r;
  Component generate, modes, oper, statics, loop;
  std::shared_ptr<const ModalBasis> basis;
  for (auto _ : state) {
    Scene scene = seed_scene(&generate);
    scene.analysis.structure_backend = StructureBackend::kModal;
    if (is_cutoff)
      scene.analysis.modal_cutoff_hz = std::atof(entry.c_str());
    else
      scene.analysis.modal_modes = std::atoi(entry.c_str());
    // RAILVSI_SEED_STATIC_CORRECTION=0: the modes without the dropped
    // modes' static flexibility at the rails (its cost is in "operator").
    const char* correction = std::getenv("RAILVSI_SEED_STATIC_CORRECTION");
    scene.analysis.modal_static_correction = !(correction && std::string(correction) == "0");
    StructureOperatorOptions mo;
    mo.structure_backend = StructureBackend::kModal;
    mo.modal_modes = scene.analysis.modal_modes;
    mo.modal_cutoff_hz = scene.analysis.modal_cutoff_hz;
    try {
      modes = measure("modes", [&] { basis = make_modal_basis(scene.structure, mo); });
    } catch (const InputError& e) {  // the modes did not converge: say so, and go on with the next entry
      std::fprintf(stderr, "[seed] modes failed: %s\n", e.what());
      state.SkipWithError(e.what());
      break;
    }
    std::shared_ptr<const StructureOperator> op;
    oper = measure("operator", [&] { op = make_structure_operator(scene, basis); });
    std::unique_ptr<Simulation> sim;
    statics = measure("statics", [&] { sim = std::make_unique<Simulation>(scene, op); });
    loop = measure("time loop", [&] { r = sim->run(); });
  }
  if (!basis) return;  // no modes: the error is reported
  if (!r.status.ok()) {
    state.SkipWithError(r.status.message().c_str());
    return;
  }
  const RunSummary& s = r.summary;
  const double steps = static_cast<double>(s.steps);
  const char* cutoff_env = std::getenv("RAILVSI_SEED_CUTOFF_HZ");
  const double cutoff_hz = cutoff_env ? std::atof(cutoff_env) : code_cutoff_hz(0.0, 0.0);
  const double acc_filtered = max_filtered_acceleration(r.histories, s.dt_s, cutoff_hz);
  state.counters["dofs"] = s.fidelity.structure_dofs;
  state.counters["modes"] = basis->num_modes();
  state.counters["static_correction"] = s.fidelity.static_correction ? 1 : 0;
  state.counters["f_max_Hz"] = basis->omega_rad_s().back() / (2.0 * std::numbers::pi);
  state.counters["f_cut_Hz"] = cutoff_hz;
  state.counters["modes_s"] = modes.wall_s;
  state.counters["modes_cpu_s"] = modes.cpu_s;
  state.counters["operator_s"] = oper.wall_s;
  state.counters["operator_cpu_s"] = oper.cpu_s;
  state.counters["statics_s"] = statics.wall_s;
  state.counters["statics_cpu_s"] = statics.cpu_s;
  state.counters["loop_s"] = loop.wall_s;
  state.counters["loop_cpu_s"] = loop.cpu_s;
  state.counters["s_per_step"] = loop.wall_s / steps;
  state.counters["newton_per_step"] = static_cast<double>(s.newton_iterations) / steps;
  state.counters["modes_MB"] = modes.peak_mb;
  state.counters["operator_MB"] = oper.peak_mb;
  state.counters["statics_MB"] = statics.peak_mb;
  state.counters["loop_MB"] = loop.peak_mb;
  state.counters["peak_rss_MB"] = peak_rss_mb();
  state.counters["max_deck_disp"] = s.max_abs_displacement_m;
  state.counters["max_deck_acc"] = s.max_abs_acceleration_mps2;
  state.counters["max_deck_acc_filtered"] = acc_filtered;
  state.counters["max_unloading"] = s.max_unloading_ratio;
  if (const auto& ref = fe_reference()) {
    const RunSummary& fe = ref->summary;
    const double fe_filtered = max_filtered_acceleration(ref->histories, fe.dt_s, cutoff_hz);
    state.counters["fe_max_deck_disp"] = fe.max_abs_displacement_m;
    state.counters["fe_max_deck_acc"] = fe.max_abs_acceleration_mps2;
    state.counters["fe_max_deck_acc_filtered"] = fe_filtered;
    state.counters["fe_max_unloading"] = fe.max_unloading_ratio;
    state.counters["err_disp"] = s.max_abs_displacement_m / fe.max_abs_displacement_m - 1.0;
    state.counters["err_disp_history"] = displacement_history_error(r.histories, ref->histories);
    state.counters["err_acc_filtered"] = acc_filtered / fe_filtered - 1.0;
    state.counters["err_acc"] = s.max_abs_acceleration_mps2 / fe.max_abs_acceleration_mps2 - 1.0;
    state.counters["err_unloading"] = s.max_unloading_ratio - fe.max_unloading_ratio;  // absolute
  } else {
    std::fprintf(stderr, "[seed] no FE reference in this process (filtered out or failed): no errors\n");
  }
}

}  // namespace
}  // namespace railvsi

int main(int argc, char** argv) {
  using namespace railvsi;
  // As vsi does (core/huge_pages.hpp): heap memory on transparent huge pages.
  reexec_with_huge_pages(argv);
  if (const char* list = std::getenv("RAILVSI_SEED_MODES")) {
    std::string entries(list);
    for (std::size_t pos = 0; pos <= entries.size();) {
      const std::size_t comma = std::min(entries.find(',', pos), entries.size());
      const std::string entry = entries.substr(pos, comma - pos);
      if (!entry.empty())
        benchmark::RegisterBenchmark(("BM_SeedScaleKhstModal/" + entry).c_str(), BM_SeedScaleKhstModal, entry)
            ->Unit(benchmark::kSecond)
            ->Iterations(1);
      pos = comma + 1;
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

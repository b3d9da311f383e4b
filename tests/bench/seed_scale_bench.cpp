// Seed-scale benchmark (the paper's example at its size; README,
// "Performance"): a generated 3D deck of 233,292 DOFs (the paper's count),
// the 46-axle KHST of the train library at 120 m/s, dt = 2.5e-4 s, 2,000
// steps, HHT alpha = -0.05, nonlinear Hertz, each wheelset on both rails.
// It takes tens of minutes and a few GB: run by hand, never in CI:
//   OPENBLAS_NUM_THREADS=1 build/tests/bench/seed_scale_bench
// (RAILVSI_SEED_DOFS=50000 builds a smaller deck of the same kind, to try
// changes; the numbers in the README are at the full size.)
// Times are also given as a ratio to a floor measured in the same process,
// one structure solve with the cached factor:
//   overhead = (wall - setup) / (steps x t_solve)
// (the floor is 1.0 when the operator splits its solve at the rails,
// solver/rail_suffix.hpp, 2.0 otherwise).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/huge_pages.hpp"
#include "generators/deck_3d.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "solve_floor.hpp"
#include "solver/cholmod_operator.hpp"

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

void BM_SeedScaleKhst(benchmark::State& state) {
  Result r;
  Component generate, oper, statics, loop;
  double t_solve = 0.0, t_solve_cpu = 0.0;
  std::shared_ptr<const CholmodOperator> op;
  for (auto _ : state) {
    Deck3dOptions o;
    o.target_dofs = 233292;
    // A smaller model of the same kind for trying changes (not the benchmark).
    if (const char* dofs = std::getenv("RAILVSI_SEED_DOFS")) o.target_dofs = std::atoi(dofs);
    Scene scene;
    generate = measure("generate", [&] { scene.structure = make_deck_3d(o).model; });
    scene.train = load_library_train("KHST");
    scene.speed_mps = 120.0;
    scene.analysis.dt_s = 2.5e-4;
    scene.analysis.hht = HhtParameters::from_alpha(-0.05);
    scene.analysis.contact.law = "hertz";
    scene.analysis.contact.rail_lines = {0, 1};
    scene.analysis.duration_s = 2000 * 2.5e-4;
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

}  // namespace
}  // namespace railvsi

// As vsi does (core/huge_pages.hpp): heap memory on transparent huge pages.
int main(int argc, char** argv) {
  railvsi::reexec_with_huge_pages(argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

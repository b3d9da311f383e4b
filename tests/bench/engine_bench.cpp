// Engine benchmarks. Timings are reported as ratios to a floor measured in
// the same process: one structure solve (forward/backward substitution with
// the cached CHOLMOD factor) of the same model.
//   overhead = wall / (steps x t_solve)
// The condensed method needs two solves per step, so 2.0 is the floor, or
// one where the rail DOFs are ordered last in the factor (one_solve_per_step).
#include <benchmark/benchmark.h>

#include <chrono>

#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "solve_floor.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// ICE3-like train (8 coaches) at 300 km/h over three 25 m simply supported
// spans with ballasted track, nonlinear Hertz, dt = 2.5e-4 s.
Scene ice3_on_viaduct() {
  Bridge2dOptions b;
  b.spans_m = {25.0, 25.0, 25.0};
  b.deck_mass_kg_per_m = 18000.0;
  // f1 = 5 Hz: EI = m (2 L^2 f1 / pi)^2
  const double f1 = 5.0, L = 25.0;
  b.deck_EI_Nm2 = b.deck_mass_kg_per_m * std::pow(2.0 * L * L * f1 / std::numbers::pi, 2);
  b.damping_ratio = 0.02;
  Scene s;
  const auto coach = make_car_2d(testing::ice3_coach());
  for (int i = 0; i < 8; ++i) s.train.vehicles.push_back({coach, 24.775 * i});
  TrackOptions t;
  t.approach_m = s.train.length_m() + 10.0;  // the whole train starts on the track
  b.track = t;
  s.structure = make_bridge_2d(b);
  s.speed_mps = 300.0 / 3.6;
  s.analysis.dt_s = 2.5e-4;
  s.analysis.contact.law = "hertz";
  s.analysis.history_stride = 10;
  return s;
}


void BM_StructureSolve(benchmark::State& state) {
  const Scene scene = ice3_on_viaduct();
  const auto op = make_structure_operator(scene);
  auto ws = op->make_workspace();
  Vector b = Vector::Ones(op->num_dofs()), x;
  for (auto _ : state) {
    (void)op->solve(b, x, *ws);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["dofs"] = op->num_dofs();
}
BENCHMARK(BM_StructureSolve)->Unit(benchmark::kMicrosecond);

// One run of the scene and the solve floor after it, as counters.
void run_against_floor(benchmark::State& state, const Scene& scene) {
  Result r;
  double t_solve = 0.0, t_solve_cpu = 0.0, loop_cpu_s = 0.0, op_factorization_s = 0.0, op_flexibility_s = 0.0;
  bool one_solve = false;
  for (auto _ : state) {
    const Simulation sim(scene);
    const double c0 = bench::cpu_seconds();
    r = sim.run();
    loop_cpu_s = bench::cpu_seconds() - c0;
    state.PauseTiming();
    const auto op = make_structure_operator(scene);
    const double c1 = bench::cpu_seconds();
    t_solve = bench::seconds_per_solve(*op, 2000);
    t_solve_cpu = (bench::cpu_seconds() - c1) / 2000;
    op_factorization_s = op->factorization_s();
    op_flexibility_s = op->flexibility_s();
    one_solve = op->splits_at_rails();
    state.ResumeTiming();
  }
  if (!r.status.ok()) state.SkipWithError(r.status.message().c_str());
  const RunSummary& s = r.summary;
  state.counters["wall_s"] = s.wall_s;
  state.counters["setup_s"] = s.setup_s;
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["newton_per_step"] = static_cast<double>(s.newton_iterations) / static_cast<double>(s.steps);
  state.counters["structure_dofs"] = s.fidelity.structure_dofs;
  state.counters["vehicle_dofs"] = s.fidelity.vehicle_dofs;
  state.counters["contacts"] = s.fidelity.contacts;
  state.counters["solve_us"] = t_solve * 1e6;
  state.counters["overhead"] = (s.wall_s - s.setup_s) / (static_cast<double>(s.steps) * t_solve);
  // The same ratio in CPU time (the run's loop over the solve's).
  state.counters["overhead_cpu"] = loop_cpu_s / (static_cast<double>(s.steps) * t_solve_cpu);
  // The setup's parts (wall): the factor of K_bar and the rail flexibility.
  state.counters["factorization_s"] = op_factorization_s;
  state.counters["flexibility_s"] = op_flexibility_s;
  // 1: the step costs one solve (rail DOFs last in the factor); 0: two.
  state.counters["one_solve_per_step"] = one_solve ? 1.0 : 0.0;
  state.counters["max_unloading"] = s.max_unloading_ratio;
  state.counters["max_deck_acc"] = s.max_abs_acceleration_mps2;
}
void BM_Ice3Viaduct300(benchmark::State& state) { run_against_floor(state, ice3_on_viaduct()); }
BENCHMARK(BM_Ice3Viaduct300)->Unit(benchmark::kSecond)->Iterations(1);

// The example job as `vsi simulate` runs it (the same viaduct on the German
// low-interference profile; every step stored in the histories).
void BM_Ice3ViaductGermanJob(benchmark::State& state) {
  run_against_floor(state, load_scene(RAILVSI_EXAMPLES_DIR "/viaduct-ice3-german.json"));
}
BENCHMARK(BM_Ice3ViaductGermanJob)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace railvsi

BENCHMARK_MAIN();

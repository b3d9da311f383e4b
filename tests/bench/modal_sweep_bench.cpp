// The modal moving-force rung on the standard EN 1991-2 sweep: HSLM-A1 to
// A10 x 101 speeds (100-400 km/h) over a 15 m simply supported span,
// f0 = 5 Hz, 15 t/m, 1 %, modes up to max(30 Hz, 1.5 f0, f3) = 45 Hz.
// Reported as ratios to floors measured in the same process:
//   per job / bare recurrence of that job (the modal steps alone, loads
//   precomputed), and per job against one FE-rung job at the same dt.
// Run by hand: build/tests/bench/modal_sweep_bench
#include <ctime>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/modal_moving_forces.hpp"
#include "../engine/test_scenes.hpp"
#include "cpu_time.hpp"
#include "generators/bridge_2d.hpp"
#include "io/train_loader.hpp"
#include "integration/modal_recurrence.hpp"
#include "simulation/simulation.hpp"

namespace {

using namespace railvsi;
// CPU time of this thread: the machine may be shared, the ratios must not
// depend on it.
double cpu_s() { return bench::thread_cpu_s(); }

}  // namespace

int main() {
  const auto structure = make_bridge_2d(testing::hslm_check_span_options());
  const double dt = 1.0e-3;  // samples 45 Hz 22 times a period; the recurrence has no period error
  ModalMovingForceOptions mo;
  // The code frequency max(30 Hz, 1.5 f0, f3) = f3 = 45 Hz, with a margin of
  // 20 % so that the mode at f3 is kept whatever its discretization error.
  mo.max_frequency_hz = 1.2 * 45.0;

  // One basis for the whole sweep (the batched path), built once.
  const double tb = cpu_s();
  const ModalBasis basis(structure, mo);
  const double basis_s = cpu_s() - tb;
  long jobs = 0, steps = 0;
  double wall = 0.0, bare = 0.0, setup = 0.0;
  int modes = 0;
  for (int a = 1; a <= 10; ++a) {
    Scene s;
    s.structure = structure;
    s.train = load_library_train("HSLM-A" + std::to_string(a));
    s.analysis.dt_s = dt;
    for (int v = 100; v <= 400; v += 3) {
      s.speed_mps = v / 3.6;
      const double t0 = cpu_s();
      const Result r = run_modal_moving_forces(s, basis);
      wall += cpu_s() - t0;
      setup += r.summary.setup_s;
      steps += r.summary.steps;
      ++jobs;
      if (modes == 0) std::sscanf(r.summary.fidelity.structure_backend.c_str(), "modal (%d", &modes);
    }
  }
  // Floor: the bare recurrence of the same number of steps and modes.
  std::vector<ModalStep> ms;
  for (int k = 0; k < modes; ++k) ms.push_back(make_modal_step(2 * std::numbers::pi * 5.0 * (k + 1) * (k + 1), 0.01, dt));
  std::vector<double> q(static_cast<std::size_t>(modes), 0.0), qd(q), p(q);
  double sink = 0.0;
  const double t1 = cpu_s();
  for (long n = 0; n < steps; ++n)
    for (int k = 0; k < modes; ++k) sink += ms[static_cast<std::size_t>(k)].advance(q[k], qd[k], p[k], 1e-3 * n);
  bare = cpu_s() - t1;
  // One FE-rung job at the same dt, for scale.
  Scene s;
  s.structure = structure;
  s.train = load_library_train("HSLM-A1");
  s.analysis.dt_s = dt;
  s.speed_mps = 250 / 3.6;
  const double t2 = cpu_s();
  const Result fe = Simulation(s).run();
  const double fe_s = cpu_s() - t2;
  std::printf("modal sweep: %ld jobs, %d modes, %ld steps in all; modes once %.4f s; runs CPU %.3f s (%.1f jobs/s, "
              "%.3f ms/job), of which setup %.3f s (wall)\n",
              jobs, modes, steps, basis_s, wall, jobs / wall, 1e3 * wall / jobs, setup);
  // The same sweep computing the modes in every job (the unbatched path), on a tenth of the jobs.
  double unbatched = 0.0;
  long unbatched_jobs = 0;
  for (int v = 100; v <= 400; v += 3) {
    Scene s;
    s.structure = structure;
    s.train = load_library_train("HSLM-A1");
    s.analysis.dt_s = dt;
    s.speed_mps = v / 3.6;
    const double t0 = cpu_s();
    (void)run_modal_moving_forces(s, mo);
    unbatched += cpu_s() - t0;
    ++unbatched_jobs;
  }
  std::printf("unbatched (modes in every job): %.3f ms/job\n", 1e3 * unbatched / unbatched_jobs);
  std::printf("bare recurrence of the same steps: %.4f s; per job / bare = %.1f\n", bare, wall / bare);
  std::printf("one FE-rung job (HSLM-A1, 250 km/h, %ld steps): %.3f ms; modal job / FE job = %.3f (sink %g)\n",
              fe.summary.steps, 1e3 * fe_s, wall / jobs / fe_s, sink);
  return 0;
}

#include "analysis/modal_moving_forces.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "analysis/modal_run_warnings.hpp"
#include "core/input_error.hpp"
#include "simulation/load_model.hpp"
#include "simulation/run_monitor.hpp"
#include "simulation/simulation.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

DeckOutputCorrection deck_output_correction(const Scene& scene) {
  return scene.analysis.modal_static_correction ? DeckOutputCorrection::kStatic : DeckOutputCorrection::kNone;
}

Result run_modal_moving_forces(const Scene& scene, const ModalBasis& basis) {
  return run_modal_moving_forces(scene, basis, deck_output_correction(scene));
}

Result run_modal_moving_forces(const Scene& scene, const ModalBasis& basis, DeckOutputCorrection correction) {
  const auto t_start = Clock::now();
  if (!scene.train.is_moving_forces())
    throw InputError("/train", "the modal moving-force rung needs a train of moving forces");
  if (&basis.structure() != scene.structure.get())
    throw InputError("/structure", "the modal basis was computed for another structure");
  const auto& rails = scene.analysis.contact.rail_lines;
  const ModalSweep sweep(basis, scene.train, rails, scene.analysis.dt_s,
                         scene.fidelity.asks_section_forces() ? modal_section_forces(basis, rails) : nullptr,
                         correction);
  ModalSweepWorkspace ws;
  Result result;
  const long n_steps = modal_run_steps(scene);
  result.summary.setup_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  const ModalSweepRun run =
      sweep.run(modal_run_start_x_m(scene), scene.speed_mps, n_steps, ws, &result.histories, scene.analysis.history_stride);
  result.status = run.status;
  fill_modal_summary(sweep, run, result.summary);
  result.summary.warnings = modal_run_warnings(scene);
  result.summary.wall_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

double modal_run_start_x_m(const Scene& scene) { return scene.start_x_m.value_or(default_start_x_m(scene)); }

long modal_run_steps(const Scene& scene) {
  const double duration = scene.analysis.duration_s.value_or(default_duration_s(scene, modal_run_start_x_m(scene)));
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw InputError("/analysis/duration_s", "the run has no duration: give speed_kmh > 0 or analysis.duration_s");
  const double steps = std::ceil(duration / scene.analysis.dt_s - 1e-9);
  // The FE rungs' step limit (Simulation): the sweep keeps the deck response
  // of every step, so a run of 4e7 steps took 3.9 GB, and more ended in
  // bad_alloc.
  const RunLimits limits;
  if (!scene.analysis.allow_large_run && !(steps <= limits.max_steps))
    throw InputError("/analysis/dt_s",
                     fmt::format("the run would take {:.3g} steps (limit {:.3g}): {:.6g} s of simulated time at dt = "
                                 "{:.3g} s; check dt_s, duration_s and speed_kmh (a planned dt follows the structure's "
                                 "frequencies and accuracy.tolerance), or run it with --allow-large",
                                 steps, limits.max_steps, duration, scene.analysis.dt_s));
  return static_cast<long>(steps);
}

void fill_modal_summary(const ModalSweep& sweep, const ModalSweepRun& run, RunSummary& sum) {
  const StructureModel& s = sweep.basis().structure();
  sum.dt_s = sweep.dt_s();
  sum.steps = run.steps;
  FidelityRecord& f = sum.fidelity;
  f.model = load_model_name(LoadModel::kMovingForces);
  f.contact_law = "none";
  f.solver_path = "modal-exact";
  f.structure_backend = fmt::format("modal ({} modes up to {:.4g} Hz, exact recurrence{})", sweep.num_modes(),
                                    sweep.basis().max_frequency_hz(),
                                    sweep.correction() == DeckOutputCorrection::kStatic
                                        ? ", static correction of the modes above at the output points"
                                        : "");
  f.structure_dofs = s.num_dofs();
  f.dt_s = sweep.dt_s();
  f.modes = sweep.num_modes();
  f.static_correction = sweep.correction() == DeckOutputCorrection::kStatic;
  f.modal_cutoff_hz = sweep.basis().max_frequency_hz();
  sum.supports.clear();
  sum.section_forces_note.clear();
  sum.points.clear();
  for (std::size_t i = 0; i < s.outputs().size(); ++i) {
    PointSummary point;
    point.name = s.outputs()[i].name;
    point.x_m = s.outputs()[i].x_m;
    point.max_abs_displacement_m = run.max_abs_displacement_m[i];
    point.max_abs_acceleration_mps2 = run.max_abs_acceleration_mps2[i];
    sum.points.push_back(std::move(point));
    sum.max_abs_displacement_m = std::max(sum.max_abs_displacement_m, run.max_abs_displacement_m[i]);
    sum.max_abs_acceleration_mps2 = std::max(sum.max_abs_acceleration_mps2, run.max_abs_acceleration_mps2[i]);
  }
  sum.max_abs_deck_twist_m = run.max_abs_twist_m;
  sum.deck_twist_x_m = run.twist_x_m;
  sum.deck_twist_note = sweep.twist_gauge().unavailable;
  if (run.sections)
    run.sections->summarize(sum);
  else
    sum.section_forces_note = s.info().deck_beam ? kSectionForcesNotAsked : make_section_forms(s).unavailable;
}

Result run_modal_moving_forces(const Scene& scene, const ModalMovingForceOptions& options) {
  const auto t_start = Clock::now();
  const ModalBasis basis(scene.structure, options);
  const double modes_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  Result r = run_modal_moving_forces(scene, basis);
  r.summary.setup_s += modes_s;
  r.summary.wall_s += modes_s;
  return r;
}

}  // namespace railvsi

#pragma once
// The modal rung for moving forces: the structure's own modes (Lanczos on
// its K and M, as modal_analysis), each modal equation stepped exactly for
// loads linear within a step (integration/modal_recurrence), the modes
// sampled under each axle with the rail's Hermite rows. No period error and
// no numerical damping: the time step only samples the load and the output.
// What it gives up against the FE rung: the modes above the cut-off, and
// the coupling terms of a non-proportional damping matrix (each mode keeps
// phi^T C phi / (2 omega), recorded in the fidelity). Section forces of a
// beam deck by the mode-acceleration method (simulation/modal_section_forces).
#include "analysis/modal_sweep.hpp"
#include "solver/modal_basis.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

using ModalMovingForceOptions = ModalBasisOptions;

// The Result has the same histories and summary as the FE rung's
// (Simulation::run) for a train of moving forces; its fidelity names the
// backend "modal" with the mode count. Throws InputError for a scene that
// is not a train of moving forces or whose modes cannot be computed.
// `basis` must be of scene.structure (else InputError): runs on one
// structure share one basis, so a sweep computes its modes once.
// `correction`: whether the outputs get the static response of the modes
// above the cut-off (modal_sweep.hpp; kNone is the kept modes alone, as a
// truncated modal series); without it, as the scene says
// (deck_output_correction).
Result run_modal_moving_forces(const Scene& scene, const ModalBasis& basis);
Result run_modal_moving_forces(const Scene& scene, const ModalBasis& basis, DeckOutputCorrection correction);
// The scene's analysis.static_correction (default true) on this rung.
DeckOutputCorrection deck_output_correction(const Scene& scene);
// Convenience: computes the basis for this run alone.
Result run_modal_moving_forces(const Scene& scene, const ModalMovingForceOptions& options = {});

// The pieces a sweep uses to run many speeds on one ModalSweep with the
// same bits as run_modal_moving_forces: where the first axle starts, how
// many steps, and the summary of a run (maxima, sizes, fidelity).
double modal_run_start_x_m(const Scene& scene);
long modal_run_steps(const Scene& scene);
void fill_modal_summary(const ModalSweep& sweep, const ModalSweepRun& run, RunSummary& summary);

}  // namespace railvsi

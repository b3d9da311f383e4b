#pragma once
// What the mode solvers are asked (ModalOptions) and give (ModalResult):
// the lowest eigenpairs of K phi = omega^2 M phi.
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"

namespace railvsi {

enum class ModeSolver {
  kAuto,      // Lanczos
  // Shift-invert Lanczos (Spectra) on slices of the spectrum, each
  // certified by a Sturm count (solver/lanczos_slices.hpp).
  kLanczos,
  // Subspace iteration on a block of twice the wanted modes, one shift
  // below the spectrum (solver/subspace_iteration.hpp); with a cut-off,
  // its count comes from a Sturm count.
  kSubspace,
};

// Who factorizes K - sigma M for a shift inside the spectrum (L D L', the
// Sturm count): MUMPS's multifrontal factor (BLAS-3; the default), or
// CHOLMOD's simplicial one (column by column: minutes per shift on a
// 200,000-DOF model). Below the spectrum it is always CHOLMOD's L L'.
enum class IndefiniteFactorizer { kMumps, kCholmodSimplicial };

struct ModalOptions {
  // The lowest `modes` eigenpairs; with max_frequency_hz > 0, every mode up
  // to that frequency (the count certified by a Sturm count) and at least
  // `modes` of them (modes may then be 0).
  int modes = 6;
  double max_frequency_hz = 0.0;
  ModeSolver solver = ModeSolver::kAuto;
  // The first shift sigma in (rad/s)^2. It must lie below the lowest
  // eigenvalue, so that K - sigma M is positive definite (its L L' factor
  // proves it): a small negative value does that for any constrained (or
  // merely semi-definite) K and positive definite M. Lanczos puts its next
  // shifts inside the spectrum itself.
  double shift_rad2_per_s2 = -1.0;
  IndefiniteFactorizer indefinite = IndefiniteFactorizer::kMumps;
  // The Sturm count of the modes below max_frequency_hz, made already by
  // the caller (count_modes_below: one L D L' factor at the cut-off); -1:
  // none. With it and a first factor below the spectrum, Lanczos asks
  // exactly that many pairs nearest the first shift and accepts them when
  // every one lies below the cut-off (that many eigenpairs in the interval
  // the count covers are all of them): no factor of its own at the cut-off
  // and no modes beyond it. Else it slices as without the count.
  int modes_below_cutoff = -1;
  // Lanczos: eigenpairs converged per shift (spectrum slice). Fewer cost
  // more factors, more cost a larger basis (its dense work grows as its
  // square); see tests/bench/mode_solver_bench.cpp.
  int slice_modes = 30;
  // Spectra's implicit restarts per slice: a slice not converged in
  // slice_restarts is asked again with half its modes (its edge fell inside
  // a group of nearly equal ones), down to 2 modes with
  // lanczos_max_restarts. And Spectra's tolerance.
  int slice_restarts = 50;
  // Lanczos vectors per solve with a slice's factor: > 1 is block Lanczos
  // (solver/block_lanczos.hpp; the factor read once per block: the hybrid
  // structure's bridge interior uses 16), 1 Spectra's single-vector Lanczos.
  // Not the default: on a slice inside the track's dense band of nearly
  // equal modes, block Lanczos's residual estimate was too optimistic
  // (pairs returned with |K phi - lambda M phi| / |K phi| up to 8.6e-4,
  // tests/engine/mode_solvers_test.cpp, 2026-11-27); not yet understood.
  int lanczos_block = 1;
  int lanczos_max_restarts = 1000;
  double lanczos_tolerance = 1e-12;
  // Subspace iteration: the largest relative residual of a wanted pair.
  int max_subspace_iterations = 200;
  double subspace_tolerance = 1e-8;
};

struct ModalResult {
  Status status;
  std::vector<double> frequencies_hz;  // ascending
  DenseMatrix shapes;                  // one column per mode, phi^T M phi = 1
  ModeSolver solver = ModeSolver::kLanczos;  // the one that ran
  int iterations = 0;      // of subspace iteration (also when it failed), or Lanczos restarts over the slices
  int factorizations = 0;  // of K - sigma M (Lanczos: one per shift)
  double factor_cpu_s = 0.0;  // their CPU time (this thread's)
  // With lanczos_block > 1: the largest true relative residual
  // |K phi - w^2 M phi| / |K phi| of the block pairs, and whether it
  // exceeded kMaxBlockLanczosResidual so that the modes were computed again
  // one vector at a time (max_residual is then theirs).
  double block_residual = 0.0;
  bool block_fallback = false;
  double max_residual = 0.0;
};

// Block Lanczos's own stopping test was seen to be optimistic inside bands
// of nearly equal modes (true residuals 1e-7 to 8.6e-4 where it stopped at
// 1e-12), so its pairs are accepted on their true residual alone. Measured:
// the hybrid bridge interior of the 20,000-DOF deck 3.3e-8 and at seed
// scale 2.33e-8 (kept, values against FE unchanged); one vector at a time
// gives about 1e-12 (hybrid_bench, tests/engine/hybrid_structure_test.cpp,
// 2026-11-27).
inline constexpr double kMaxBlockLanczosResidual = 1e-6;

}  // namespace railvsi

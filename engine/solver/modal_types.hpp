#pragma once
// What the mode solvers are asked (ModalOptions) and give (ModalResult):
// the lowest eigenpairs of K phi = omega^2 M phi.
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"

namespace railvsi {

// Lanczos converges slowly when many wanted modes come in groups of nearly
// equal ones (a 3D deck of equal spans: 48 modes of a 15,000-DOF deck took
// 81 s, against 2.6 s by subspace iteration); subspace iteration converges
// slowly when a dense group of modes follows the wanted ones (the
// sleeper-on-ballast modes of a track: 24 modes of a viaduct with track were
// not converged after 200 iterations, against 0.2 s by Lanczos).
enum class ModeSolver {
  // From subspace_from_dofs (3D decks) subspace iteration, else Lanczos
  // within auto_lanczos_restarts; the other one when the first misses.
  kAuto,
  kLanczos,   // Spectra, one vector at a time
  kSubspace,  // a block of twice the wanted modes
};

struct ModalOptions {
  int modes = 6;
  ModeSolver solver = ModeSolver::kAuto;
  // Shift sigma in (rad/s)^2. It must lie below the lowest eigenvalue, so
  // that K - sigma M is positive definite and the eigenvalues nearest to it
  // are the lowest ones: a small negative value does that for any
  // constrained (or merely semi-definite) K and positive definite M.
  double shift_rad2_per_s2 = -1.0;
  // Lanczos: Spectra iterations (implicit restarts) per attempt, and
  // kAuto's budget for its first attempt (a viaduct with track needs 16 for
  // 24 modes and goes the long way, +0.25 s; a 15,000-DOF deck's 48 modes
  // cost 8.2 s instead of 15.5 s with a budget of 30).
  int lanczos_max_restarts = 1000;
  int auto_lanczos_restarts = 10;
  // Eigenpairs the Lanczos iteration converges (the lowest `modes` of them
  // are returned): at least this many and twice the modes, doubled after a
  // failure up to max_lanczos_pairs. See modal_analysis.cpp for why.
  int min_lanczos_pairs = 40;
  int max_lanczos_pairs = 320;
  double lanczos_tolerance = 1e-10;  // Spectra's
  // Subspace iteration: the largest relative residual of a wanted pair.
  int max_subspace_iterations = 200;
  double subspace_tolerance = 1e-8;
  // kAuto takes subspace iteration first from this many DOFs (the 3D decks).
  Eigen::Index subspace_from_dofs = 20000;
};

struct ModalResult {
  Status status;
  std::vector<double> frequencies_hz;  // ascending
  DenseMatrix shapes;                  // one column per mode, phi^T M phi = 1
  ModeSolver solver = ModeSolver::kLanczos;  // the one that ran
  int iterations = 0;                  // of subspace iteration, also when it failed (0 for Lanczos)
};

}  // namespace railvsi

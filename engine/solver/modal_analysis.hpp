#pragma once
// Natural frequencies and mode shapes: the lowest eigenpairs of
// K phi = omega^2 M phi on a CHOLMOD factor of K - sigma M, by Lanczos in
// shift-invert mode (Spectra) or by subspace iteration
// (solver/subspace_iteration.hpp).
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// Lanczos converges slowly when many wanted modes come in groups of nearly
// equal ones (a 3D deck of equal spans: 48 modes of a 15,000-DOF deck took
// 81 s, against 2.6 s by subspace iteration); subspace iteration converges
// slowly when a dense group of modes follows the wanted ones (the
// sleeper-on-ballast modes of a track: 24 modes of a viaduct with track were
// not converged after 200 iterations, against 0.2 s by Lanczos).
enum class ModeSolver {
  // From kSubspaceFromDofs (3D decks) subspace iteration, else Lanczos
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
  int max_iterations = 1000;
  // kAuto's first Lanczos attempt, in Spectra iterations (restarts).
  int auto_lanczos_restarts = 30;
  // Eigenpairs the Lanczos iteration converges (the lowest `modes` of them
  // are returned): at least this many and twice the modes, doubled after a
  // failure up to max_lanczos_pairs. See modal_analysis.cpp for why.
  int min_lanczos_pairs = 40;
  int max_lanczos_pairs = 320;
  double tolerance = 1e-10;
  // Subspace iteration: the largest relative residual of a wanted pair.
  int max_subspace_iterations = 200;
  double subspace_tolerance = 1e-8;
};

// kAuto's switch to subspace iteration (see modal_analysis.cpp).
inline constexpr Eigen::Index kSubspaceFromDofs = 20000;

struct ModalResult {
  Status status;
  std::vector<double> frequencies_hz;  // ascending
  DenseMatrix shapes;                  // one column per mode, phi^T M phi = 1
  ModeSolver solver = ModeSolver::kLanczos;  // the one that ran
  int iterations = 0;                  // of subspace iteration (0 for Lanczos)
};

// K and M symmetric (full storage), M positive definite. Fewer modes than
// asked when the model has fewer than modes + 1 DOFs. A failed
// factorization or a Lanczos that does not converge is a Status, not an
// exception.
ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options = {});
ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options = {});

}  // namespace railvsi

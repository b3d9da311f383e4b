#pragma once
// Natural frequencies and mode shapes: the lowest eigenpairs of
// K phi = omega^2 M phi, by Lanczos in shift-invert mode (Spectra) on a
// CHOLMOD factor of K - sigma M.
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

struct ModalOptions {
  int modes = 6;
  // Shift sigma in (rad/s)^2. It must lie below the lowest eigenvalue, so
  // that K - sigma M is positive definite and the eigenvalues nearest to it
  // are the lowest ones: a small negative value does that for any
  // constrained (or merely semi-definite) K and positive definite M.
  double shift_rad2_per_s2 = -1.0;
  int max_iterations = 1000;
  // Eigenpairs the Lanczos iteration converges (the lowest `modes` of them
  // are returned): at least this many and twice the modes, doubled after a
  // failure up to max_lanczos_pairs. See modal_analysis.cpp for why.
  int min_lanczos_pairs = 40;
  int max_lanczos_pairs = 320;
  double tolerance = 1e-10;
};

struct ModalResult {
  Status status;
  std::vector<double> frequencies_hz;  // ascending
  DenseMatrix shapes;                  // one column per mode, phi^T M phi = 1
};

// K and M symmetric (full storage), M positive definite. Fewer modes than
// asked when the model has fewer than modes + 1 DOFs. A failed
// factorization or a Lanczos that does not converge is a Status, not an
// exception.
ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options = {});
ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options = {});

}  // namespace railvsi

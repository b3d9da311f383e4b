#pragma once
// Natural frequencies and mode shapes: the lowest eigenpairs of
// K phi = omega^2 M phi on a CHOLMOD factor of K - sigma M, by Lanczos in
// shift-invert mode (Spectra) or by subspace iteration
// (solver/subspace_iteration.hpp).
#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/modal_types.hpp"

namespace railvsi {

// K and M symmetric (full storage), M positive definite. Fewer modes than
// asked when the model has fewer than modes + 1 DOFs. A failed
// factorization or a Lanczos that does not converge is a Status, not an
// exception.
ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options = {});
ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options = {});

}  // namespace railvsi

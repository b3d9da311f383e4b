#pragma once
// Natural frequencies and mode shapes: the lowest eigenpairs of
// K phi = omega^2 M phi (a count, or every one up to a cut-off), by
// shift-invert Lanczos on slices of the spectrum (solver/lanczos_slices.hpp)
// or by subspace iteration (solver/subspace_iteration.hpp).
#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/modal_types.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {

// K and M symmetric (full storage), M positive definite. Fewer modes than
// asked when the model has fewer than modes + 1 DOFs (at most n - 1). The
// sign of a Lanczos shape: its largest entry positive. A failed
// factorization or a Lanczos that does not converge is a Status, not an
// exception.
// `first_factor`: an L L' factor of K - sigma M at options.shift_rad2_per_s2
// already made (a substructure's K for its static modes), Lanczos's first
// shift; null: factorized here.
ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options = {},
                           const ShiftInvertFactor* first_factor = nullptr);
ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options = {});

}  // namespace railvsi

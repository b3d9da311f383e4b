#pragma once
// The lowest eigenpairs of K phi = lambda M phi by shift-invert Lanczos on
// slices of the spectrum (after Grimes, Lewis and Simon, SIAM J. Matrix
// Anal. Appl. 15(1), 1994). Slice j has a shift sigma_j and one factor of
// K - sigma_j M (L L' below the spectrum, then L D L'); Lanczos (Spectra)
// converges the eigenvalues nearest sigma_j, M-orthogonal to every mode
// found before (deflated), and keeps those above sigma_j. The next shift
// goes in the widest gap near the top of those, and its factor's inertia
// (the Sturm count) says how many eigenvalues lie between the two shifts:
// the slice is accepted only when it found exactly that many, else it is
// searched again, deflated against what it found. So the result is
// certified complete (a multiple eigenvalue is never missed), each shift
// costs one factor, and the Lanczos basis stays about twice the slice
// however many modes are wanted. A slice whose edge falls inside a group of
// nearly equal modes (the track's rail-on-pad modes agree to 1e-7) does not
// converge in ModalOptions::slice_restarts; it is asked again with half its
// modes, so that the next shift comes close to the group and spreads it.
#include "core/types.hpp"
#include "solver/modal_types.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {

// The lowest max(modes, count below the cut-off) eigenpairs of K, M (the
// cut-off is options.max_frequency_hz when > 0; `modes` may be 0 then);
// never more than n - 1. Frequencies ascending, shapes M-orthonormal.
// `first`: an L L' factor at options.shift_rad2_per_s2 (below the spectrum)
// to start from, not counted in the result's factorizations; null: made here.
ModalResult lanczos_slices(const SparseMatrix& K, const SparseMatrix& M, Eigen::Index modes,
                           const ModalOptions& options, const ShiftInvertFactor* first = nullptr);

// The number of eigenvalues of K phi = omega^2 M phi with a frequency below
// frequency_hz (one L D L' factor; -1 with the status when it fails).
Eigen::Index count_modes_below(const SparseMatrix& K, const SparseMatrix& M, double frequency_hz,
                               Status* status = nullptr,
                               IndefiniteFactorizer indefinite = IndefiniteFactorizer::kMumps);

}  // namespace railvsi

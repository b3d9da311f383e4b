#pragma once
// The lowest eigenpairs of K phi = lambda M phi by subspace iteration with
// Rayleigh-Ritz (Bathe, "Finite Element Procedures", 2nd ed. 2014, section
// 11.6): X <- (K - sigma M)^-1 M X on a block of p vectors, then the p x p
// projected problem. Mode i converges by the ratio
// (lambda_i - sigma) / (lambda_{p+1} - sigma) per iteration whatever the
// gaps between the wanted modes, so a structure of identical spans, whose
// modes come in near-equal groups, costs no more than any other. Each
// iteration is one block solve on the factor (BLAS-3) and dense products.
#include "core/types.hpp"
#include "solver/modal_types.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {

// The lowest `modes` eigenpairs (modes < n), factor factorized at the shift.
// Converged when every wanted pair has a relative residual
// |K phi - lambda M phi| / |(K - sigma M) phi| below
// options.subspace_tolerance.
ModalResult subspace_iteration(const SparseMatrix& K, const SparseMatrix& M, Eigen::Index modes,
                               const ShiftInvertFactor& factor, const ModalOptions& options);

}  // namespace railvsi

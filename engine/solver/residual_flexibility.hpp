#pragma once
// The static flexibility that a truncated modal basis leaves out, at the
// rail DOFs: R = F_rail - Phi_r Omega^-2 Phi_r^T, with F_rail = K^-1 at the
// rail DOFs (exact, from a factor of K) and Phi_r the kept modes' rows
// there (mass-normalised, K^-1 = sum_k phi_k phi_k^T / omega_k^2 over all
// modes). R is the quasi-static response of the dropped modes: the static
// correction of the mode-acceleration method (Cornwell, Craig & Johnson,
// Earthquake Eng. Struct. Dyn. 11, 1983) and the residual flexibility of
// modal truncation augmentation (Dickens, Nakagawa & Wittbrodt, Computers &
// Structures 62(6), 1997). Under a wheel it is the local flexibility of the
// track's high modes, which the kept modes miss.
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// F_rail - Phi_r^T diag(omega^-2) Phi_r: `F_rail` n x n, `rail_rows` the
// kept modes at the same n DOFs (one column per DOF, one row per mode).
DenseMatrix residual_flexibility(const DenseMatrix& F_rail, const DenseMatrix& rail_rows,
                                 const std::vector<double>& omega_rad_s);
// The same between two sets of DOFs: F - Phi_a^T diag(omega^-2) Phi_b, with
// F = K^-1 at rows a and columns b, `rows_a` and `rows_b` the kept modes
// there (one column per DOF, one row per mode).
DenseMatrix residual_flexibility(const DenseMatrix& F, const DenseMatrix& rows_a, const DenseMatrix& rows_b,
                                 const std::vector<double>& omega_rad_s);

// K^-1 at the model's rail DOFs (StructureModel::rail_dofs() order), from a
// CHOLMOD factor of K. Throws InputError when K cannot be factorized.
DenseMatrix static_rail_flexibility(const StructureModel& model);

}  // namespace railvsi

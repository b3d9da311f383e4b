#pragma once
// The bridge's static constraint modes Psi = -K_II^-1 K_IG from one L L'
// factor of the whole bridge K_BB (interior I, then interface G) with the
// interface ordered last. In that order
//
//   P K_BB P' = L L',  L = [L_II 0; L_GI L_GG],
//
// L_II is K_II's factor and L_GI = K_GI L_II^-T, so
// Psi = -P_I' L_II^-T L_GI': one backward solve per interface column where
// a factor of K_II alone needs a forward one too. The same factor is the bridge's modes' shift-invert operator
// at shift 0 (hybrid_basis.cpp): one factor of the bridge instead of two.
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {

// The ordering of K_BB (its first n_interior DOFs the interior, the last
// n_interface the interface) for ShiftInvertFactor::order_as: the interior
// in CHOLMOD's fill-reducing order of K_II alone (postordered for K_II's
// elimination tree, so L_II keeps its supernodes), then the interface in
// its own order. Empty, with the Status, when CHOLMOD cannot analyze K_II.
std::vector<int> interface_last_ordering(const SparseMatrix& K_II, int n_interface, Status& status);

// Psi (n_interior x n_interface, the interior in K_BB's order) from
// `factor`, an L L' factor of K_BB ordered by interface_last_ordering,
// `column_block` interface columns per backward solve. False when the
// factor is not such a CHOLMOD L L' factor or a solve fails.
bool constraint_modes(const ShiftInvertFactor& factor, int n_interior, int column_block, DenseMatrix& Psi);

}  // namespace railvsi

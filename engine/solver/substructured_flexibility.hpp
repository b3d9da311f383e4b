#pragma once
// Columns of K^-1 at a set of DOFs W (the rail flexibility, or the static
// flexibility under the wheels), with solves of the whole structure only
// where the deck is involved. The track away from the deck (the approach and
// exit rails on rigid ground, and rail DOFs that only couple to other track
// DOFs) is a substructure T whose matrix A = K(T,T) is small and banded. For
// a column j in T, the rows T of K y = e_j read
//   A y_T + K(T,G) y_G = e_j(T),
// G the DOFs outside T coupled to T, and by symmetry y_G = K^-1(j, G),
// which the solves for the columns G give. So
//   K^-1(T, j) = A^-1 (e_j(T) - K(T,G) K^-1(G, j)),
// exact in exact arithmetic: only the columns (W \ T) and G are solved with
// the factor of the whole structure, the rest with A.
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

struct SubstructureSummary {
  int direct_columns = 0;    // columns solved with the whole structure's factor
  int substructure_dofs = 0; // |T| (0: no substructure used, all columns direct)
};

// K^-1(W, W) for the matrix K that `op` inverts (K must be that matrix: the
// effective matrix of the operator, or the static stiffness). Falls back to
// op.flexibility_block when no track substructure saves solves, or (with
// by_cost) when the solves it saves cost less than the work on the
// substructure (small plane models, whose solves take microseconds).
DenseMatrix substructured_flexibility(const StructureOperator& op, const SparseMatrix& K,
                                      const StructureModel& model, const std::vector<int>& dofs,
                                      SolveWorkspace& ws, SubstructureSummary* summary = nullptr,
                                      bool by_cost = true);

}  // namespace railvsi

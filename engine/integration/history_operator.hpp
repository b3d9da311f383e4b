#pragma once
// The history part of the HHT right-hand side for a sparse subsystem,
//   rhs = M (c0 u + c1 v + c2 a) + C ((1+alpha)(c3 u - c4 v - c5 a) + alpha v) + alpha K u,
// in one pass over the rows of K and C (one shared pattern) and one over the
// rows of M (often nearly diagonal, so kept apart) instead of three sparse
// products. The same pass gives the products of the state that the energy
// balance needs (K u, C v, M v, M a), so the time loop reads the matrices
// once per step: after the two solves, the step's cost is here.
#include <vector>

#include "integration/hht.hpp"

namespace railvsi {

// Products of one state with the subsystem's matrices.
struct StateProducts {
  Vector Ku, Cv, Mv, Ma;
};

class SparseHistoryOperator {
 public:
  SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C, const SparseMatrix& K);
  // The history terms of state s into rhs; with `products`, also K u, C v,
  // M v and M a of s.
  void apply(const HhtCoefficients& h, const KinematicState& s, Vector& rhs,
             StateProducts* products = nullptr);

 private:
  int n_ = 0;
  // Rows (gathered: y_i = sum_j A_ij x_j, A's own entries whatever its
  // round-off asymmetry) of the union pattern of K and C, and of M.
  std::vector<int> kc_outer_, kc_inner_, m_outer_, m_inner_;
  std::vector<double> k_, c_, m_;
  Vector work_;  // scratch (one operator per run, in its RunState)
};

}  // namespace railvsi

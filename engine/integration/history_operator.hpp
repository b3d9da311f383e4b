#pragma once
// The history part of the HHT right-hand side for a sparse subsystem,
//   rhs = M (c0 u + c1 v + c2 a) + C ((1+alpha)(c3 u - c4 v - c5 a) + alpha v) + alpha K u,
// in one pass over the rows of the union pattern of M, C and K instead of
// three sparse products. The same pass gives the products of the state that
// the energy balance needs (K u, C v, M v, M a), so the time loop reads the
// matrices once per step: after the two solves, the step's cost is here.
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
  template <bool kProducts>
  void apply_rows(const HhtCoefficients& h, const KinematicState& s, Vector& rhs, StateProducts* products);

  int n_ = 0;
  // Rows taken two at a time (gathered: y_i = sum_j A_ij x_j, A's own
  // entries whatever its round-off asymmetry), one SIMD lane each: slot q of
  // pair r holds lane l's column and values at 2 (pair_outer_[r] + q) + l.
  // Each row's entries are its union pattern of M, C and K in column order;
  // a matrix's missing entries and the shorter row's padding are explicit
  // zeros (col: the row itself). Adding 0 * x (x finite) to a sum started at
  // +0 leaves it exactly as it was, so every sum equals the one over that matrix's own
  // row in column order, bit for bit.
  std::vector<int> pair_outer_, col_;
  std::vector<double> k_, c_, m_;
  Vector work_;  // scratch (one operator per run, in its RunState)
};

}  // namespace railvsi

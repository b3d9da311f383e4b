#pragma once
// The history part of the HHT right-hand side for a sparse subsystem,
//   rhs = M (c0 u + c1 v + c2 a) + C ((1+alpha)(c3 u - c4 v - c5 a) + alpha v) + alpha K u,
// in one pass over the union sparsity pattern of M, C and K instead of three
// sparse products (the time loop spends its time here after the solves).
#include <vector>

#include "integration/hht.hpp"

namespace railvsi {

class SparseHistoryOperator {
 public:
  SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C, const SparseMatrix& K);
  void apply(const HhtCoefficients& h, const KinematicState& s, Vector& rhs) const;

 private:
  int n_ = 0;
  std::vector<int> outer_, inner_;
  std::vector<double> m_, c_, k_;
};

}  // namespace railvsi

#include "integration/history_operator.hpp"

namespace railvsi {

SparseHistoryOperator::SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C,
                                             const SparseMatrix& K)
    : n_(static_cast<int>(M.rows())) {
  // Union pattern with explicit zeros: the sums keep every structural entry.
  SparseMatrix Z = 0.0 * M + 0.0 * C + 0.0 * K;
  SparseMatrix Mu = M + Z, Cu = C + Z, Ku = K + Z;
  Mu.makeCompressed();
  Cu.makeCompressed();
  Ku.makeCompressed();
  outer_.assign(Mu.outerIndexPtr(), Mu.outerIndexPtr() + n_ + 1);
  inner_.assign(Mu.innerIndexPtr(), Mu.innerIndexPtr() + Mu.nonZeros());
  m_.assign(Mu.valuePtr(), Mu.valuePtr() + Mu.nonZeros());
  c_.assign(Cu.valuePtr(), Cu.valuePtr() + Cu.nonZeros());
  k_.assign(Ku.valuePtr(), Ku.valuePtr() + Ku.nonZeros());
}

void SparseHistoryOperator::apply(const HhtCoefficients& h, const KinematicState& s, Vector& rhs) const {
  rhs.setZero(n_);
  const double one_alpha = 1.0 + h.alpha;
  for (int j = 0; j < n_; ++j) {
    const double u = s.u[j], v = s.v[j], a = s.a[j];
    const double wm = h.c0 * u + h.c1 * v + h.c2 * a;
    const double wc = one_alpha * (h.c3 * u - h.c4 * v - h.c5 * a) + h.alpha * v;
    const double wk = h.alpha * u;
    for (int p = outer_[j]; p < outer_[j + 1]; ++p)
      rhs[inner_[p]] += m_[p] * wm + c_[p] * wc + k_[p] * wk;
  }
}

}  // namespace railvsi

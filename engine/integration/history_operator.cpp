#include "integration/history_operator.hpp"

namespace railvsi {

namespace {
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
}

SparseHistoryOperator::SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C,
                                             const SparseMatrix& K)
    : n_(static_cast<int>(M.rows())) {
  // Union pattern of K and C with explicit zeros: the sums keep every
  // structural entry, so both value arrays share one index array.
  const SparseMatrix Z = 0.0 * C + 0.0 * K;
  RowMatrix Cu = C + Z, Ku = K + Z, Mr = M;
  Cu.makeCompressed();
  Ku.makeCompressed();
  Mr.makeCompressed();
  kc_outer_.assign(Ku.outerIndexPtr(), Ku.outerIndexPtr() + n_ + 1);
  kc_inner_.assign(Ku.innerIndexPtr(), Ku.innerIndexPtr() + Ku.nonZeros());
  k_.assign(Ku.valuePtr(), Ku.valuePtr() + Ku.nonZeros());
  c_.assign(Cu.valuePtr(), Cu.valuePtr() + Cu.nonZeros());
  m_outer_.assign(Mr.outerIndexPtr(), Mr.outerIndexPtr() + n_ + 1);
  m_inner_.assign(Mr.innerIndexPtr(), Mr.innerIndexPtr() + Mr.nonZeros());
  m_.assign(Mr.valuePtr(), Mr.valuePtr() + Mr.nonZeros());
}

void SparseHistoryOperator::apply(const HhtCoefficients& h, const KinematicState& s, Vector& rhs,
                                  StateProducts* products) {
  rhs.resize(n_);
  if (products) {
    products->Ku.resize(n_);
    products->Cv.resize(n_);
    products->Mv.resize(n_);
    products->Ma.resize(n_);
  }
  const double one_alpha = 1.0 + h.alpha;
  // The damping's history weights w_c = (1+alpha)(c3 u - c4 v - c5 a) + alpha v.
  work_ = one_alpha * (h.c3 * s.u - h.c4 * s.v - h.c5 * s.a) + h.alpha * s.v;
  const double* u = s.u.data();
  const double* v = s.v.data();
  const double* a = s.a.data();
  const double* wc = work_.data();
  for (int i = 0; i < n_; ++i) {
    double ku = 0.0, cw = 0.0, cv = 0.0;
    for (int p = kc_outer_[i]; p < kc_outer_[i + 1]; ++p) {
      const int j = kc_inner_[p];
      ku += k_[p] * u[j];
      cw += c_[p] * wc[j];
      cv += c_[p] * v[j];
    }
    double mu = 0.0, mv = 0.0, ma = 0.0;
    for (int p = m_outer_[i]; p < m_outer_[i + 1]; ++p) {
      const int j = m_inner_[p];
      mu += m_[p] * u[j];
      mv += m_[p] * v[j];
      ma += m_[p] * a[j];
    }
    rhs[i] = h.c0 * mu + h.c1 * mv + h.c2 * ma + cw + h.alpha * ku;
    if (products) {
      products->Ku[i] = ku;
      products->Cv[i] = cv;
      products->Mv[i] = mv;
      products->Ma[i] = ma;
    }
  }
}

}  // namespace railvsi

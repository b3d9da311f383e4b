#include "integration/history_operator.hpp"

#include <cstring>

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
  kc_.resize(2 * static_cast<std::size_t>(Ku.nonZeros()));
  for (Eigen::Index p = 0; p < Ku.nonZeros(); ++p) {
    kc_[2 * static_cast<std::size_t>(p)] = Ku.valuePtr()[p];
    kc_[2 * static_cast<std::size_t>(p) + 1] = Cu.valuePtr()[p];
  }
  m_outer_.assign(Mr.outerIndexPtr(), Mr.outerIndexPtr() + n_ + 1);
  m_inner_.assign(Mr.innerIndexPtr(), Mr.innerIndexPtr() + Mr.nonZeros());
  m_.assign(Mr.valuePtr(), Mr.valuePtr() + Mr.nonZeros());
}

namespace {

// Two lanes of one sum each: every lane adds its products in the order of
// the scalar loop (a multiply, then an add), so the sums are the scalar
// ones bit for bit, two per instruction.
using Pair = double __attribute__((vector_size(16)));

Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

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
  // The state by DOF, {u, v, a, w_c}: one gather reads what a row's
  // products need of a column.
  state_.resize(4 * static_cast<std::size_t>(n_));
  for (int j = 0; j < n_; ++j) {
    double* x = state_.data() + 4 * static_cast<std::size_t>(j);
    x[0] = s.u[j];
    x[1] = s.v[j];
    x[2] = s.a[j];
    x[3] = work_[j];
  }
  const double* X = state_.data();
  const double* kc = kc_.data();
  for (int i = 0; i < n_; ++i) {
    Pair ku_cv = {0.0, 0.0};  // K u, C v
    double cw = 0.0;
    for (int p = kc_outer_[i]; p < kc_outer_[i + 1]; ++p) {
      const double* x = X + 4 * static_cast<std::size_t>(kc_inner_[p]);
      ku_cv += load_pair(kc + 2 * static_cast<std::size_t>(p)) * load_pair(x);
      cw += kc[2 * static_cast<std::size_t>(p) + 1] * x[3];
    }
    Pair mu_mv = {0.0, 0.0};  // M u, M v
    double ma = 0.0;
    for (int p = m_outer_[i]; p < m_outer_[i + 1]; ++p) {
      const double* x = X + 4 * static_cast<std::size_t>(m_inner_[p]);
      const double m = m_[p];
      mu_mv += Pair{m, m} * load_pair(x);
      ma += m * x[2];
    }
    const double ku = ku_cv[0], cv = ku_cv[1], mu = mu_mv[0], mv = mu_mv[1];
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

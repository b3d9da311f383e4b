#include "integration/history_operator.hpp"

#include <cstring>

namespace railvsi {

namespace {
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
}

SparseHistoryOperator::SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C,
                                             const SparseMatrix& K)
    : n_(static_cast<int>(M.rows())) {
  // Union pattern of K, C and M with explicit zeros: the sums keep every
  // structural entry, so the three value arrays share one index array. An
  // explicit zero adds +-0 to a sum, which leaves it as it was: the sums
  // are those over each matrix's own entries.
  const SparseMatrix Z = 0.0 * C + 0.0 * K + 0.0 * M;
  RowMatrix Cu = C + Z, Ku = K + Z, Mu = M + Z;
  Cu.makeCompressed();
  Ku.makeCompressed();
  Mu.makeCompressed();
  outer_.assign(Ku.outerIndexPtr(), Ku.outerIndexPtr() + n_ + 1);
  inner_.assign(Ku.innerIndexPtr(), Ku.innerIndexPtr() + Ku.nonZeros());
  values_.resize(4 * static_cast<std::size_t>(Ku.nonZeros()));
  for (Eigen::Index p = 0; p < Ku.nonZeros(); ++p) {
    double* v = values_.data() + 4 * static_cast<std::size_t>(p);
    v[0] = Ku.valuePtr()[p];
    v[1] = Cu.valuePtr()[p];
    v[2] = Mu.valuePtr()[p];
    v[3] = 0.0;
  }
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
  const double* values = values_.data();
  for (int i = 0; i < n_; ++i) {
    Pair ku_cv = {0.0, 0.0}, mu_mv = {0.0, 0.0};  // K u, C v; M u, M v
    double cw = 0.0, ma = 0.0;
    for (int p = outer_[i]; p < outer_[i + 1]; ++p) {
      const double* x = X + 4 * static_cast<std::size_t>(inner_[p]);
      const double* v = values + 4 * static_cast<std::size_t>(p);
      const Pair uv = load_pair(x);
      ku_cv += load_pair(v) * uv;
      cw += v[1] * x[3];
      mu_mv += Pair{v[2], v[2]} * uv;
      ma += v[2] * x[2];
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

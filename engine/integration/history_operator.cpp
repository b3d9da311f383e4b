#include "integration/history_operator.hpp"

#include <algorithm>

namespace railvsi {

namespace {
using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
// Two rows at once (SSE2, every x86-64): each lane does exactly the scalar
// operations of its row, in the same order.
using Two = double __attribute__((vector_size(2 * sizeof(double))));

inline Two load2(const double* p) { return Two{p[0], p[1]}; }
inline Two gather2(const double* x, const int* col) { return Two{x[col[0]], x[col[1]]}; }
}  // namespace

SparseHistoryOperator::SparseHistoryOperator(const SparseMatrix& M, const SparseMatrix& C,
                                             const SparseMatrix& K)
    : n_(static_cast<int>(M.rows())) {
  // Union pattern of M, C and K with explicit zeros: the sums keep every
  // structural entry, so the three value arrays share one index array.
  const SparseMatrix Z = 0.0 * M + 0.0 * C + 0.0 * K;
  RowMatrix Mu = M + Z, Cu = C + Z, Ku = K + Z;
  Mu.makeCompressed();
  Cu.makeCompressed();
  Ku.makeCompressed();
  const int pairs = (n_ + 1) / 2;
  pair_outer_.assign(static_cast<std::size_t>(pairs) + 1, 0);
  const auto row_length = [&](int i) { return i < n_ ? Ku.outerIndexPtr()[i + 1] - Ku.outerIndexPtr()[i] : 0; };
  for (int r = 0; r < pairs; ++r)
    pair_outer_[r + 1] = pair_outer_[r] + std::max(row_length(2 * r), row_length(2 * r + 1));
  const auto slots = static_cast<std::size_t>(2 * pair_outer_[pairs]);
  col_.assign(slots, 0);
  k_.assign(slots, 0.0);
  c_.assign(slots, 0.0);
  m_.assign(slots, 0.0);
  for (int r = 0; r < pairs; ++r)
    for (int l = 0; l < 2; ++l) {
      const int i = 2 * r + l;
      const int len = row_length(i);
      for (int q = 0; q < pair_outer_[r + 1] - pair_outer_[r]; ++q) {
        const auto at = static_cast<std::size_t>(2 * (pair_outer_[r] + q) + l);
        if (q >= len) {  // padding (a missing row past n: column 0)
          col_[at] = i < n_ ? i : 0;
          continue;
        }
        const int p = Ku.outerIndexPtr()[i] + q;
        col_[at] = Ku.innerIndexPtr()[p];
        k_[at] = Ku.valuePtr()[p];
        c_[at] = Cu.valuePtr()[p];
        m_[at] = Mu.valuePtr()[p];
      }
    }
}

void SparseHistoryOperator::apply(const HhtCoefficients& h, const KinematicState& s, Vector& rhs,
                                  StateProducts* products) {
  if (products) apply_rows<true>(h, s, rhs, products);
  else apply_rows<false>(h, s, rhs, products);
}

template <bool kProducts>
void SparseHistoryOperator::apply_rows(const HhtCoefficients& h, const KinematicState& s, Vector& rhs,
                                       StateProducts* products) {
  rhs.resize(n_);
  if constexpr (kProducts) {
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
  const int* col = col_.data();
  const double* kv = k_.data();
  const double* cv_ = c_.data();
  const double* mv_ = m_.data();
  const Two c0{h.c0, h.c0}, c1{h.c1, h.c1}, c2{h.c2, h.c2}, al{h.alpha, h.alpha};
  const int pairs = static_cast<int>(pair_outer_.size()) - 1;
  for (int r = 0; r < pairs; ++r) {
    Two ku{0.0, 0.0}, cw{0.0, 0.0}, cv{0.0, 0.0}, mu{0.0, 0.0}, mv{0.0, 0.0}, ma{0.0, 0.0};
    for (int q = 2 * pair_outer_[r]; q < 2 * pair_outer_[r + 1]; q += 2) {
      const int* j = col + q;
      const Two uj = gather2(u, j), k = load2(kv + q), c = load2(cv_ + q), m = load2(mv_ + q);
      ku += k * uj;
      cw += c * gather2(wc, j);
      if constexpr (kProducts) cv += c * gather2(v, j);
      mu += m * uj;
      mv += m * gather2(v, j);
      ma += m * gather2(a, j);
    }
    // The scalar expression's order: ((c0 mu + c1 mv) + c2 ma) + cw + alpha ku.
    const Two out = c0 * mu + c1 * mv + c2 * ma + cw + al * ku;
    for (int l = 0; l < 2; ++l) {
      const int i = 2 * r + l;
      if (i >= n_) break;
      rhs[i] = out[l];
      if constexpr (kProducts) {
        products->Ku[i] = ku[l];
        products->Cv[i] = cv[l];
        products->Mv[i] = mv[l];
        products->Ma[i] = ma[l];
      }
    }
  }
}

}  // namespace railvsi

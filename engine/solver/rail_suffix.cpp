#include "solver/rail_suffix.hpp"

#include <cmath>

extern "C" void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);

namespace railvsi {
namespace {

std::vector<char> membership(int n, const std::vector<int>& dofs) {
  std::vector<char> in(static_cast<std::size_t>(n), 0);
  for (int d : dofs) in[static_cast<std::size_t>(d)] = 1;
  return in;
}

// A supernode's values: nsrow x nscol, column-major, its diagonal block on top.
using SupernodeBlock = Eigen::Map<const DenseMatrix, 0, Eigen::OuterStride<>>;

// The arrays of a supernodal factor (cholmod_factor's super, pi, px, s, x).
struct Supernodes {
  explicit Supernodes(const cholmod_factor& L)
      : super(static_cast<const int*>(L.super)), pi(static_cast<const int*>(L.pi)),
        px(static_cast<const int*>(L.px)), s(static_cast<const int*>(L.s)), x(static_cast<const double*>(L.x)),
        count(static_cast<int>(L.nsuper)) {}
  struct Block {
    int k1, nscol, nsrow;  // first column, columns, rows
    const int* rows;       // row indices, the block's own columns first
    SupernodeBlock X;
  };
  Block block(int k) const {
    const int nscol = super[k + 1] - super[k], nsrow = pi[k + 1] - pi[k];
    return {super[k], nscol, nsrow, s + pi[k], SupernodeBlock(x + px[k], nsrow, nscol, Eigen::OuterStride<>(nsrow))};
  }
  // The supernode holding column j.
  int at(int j) const {
    int k = count;
    while (k > 0 && super[k] > j) --k;
    return k;
  }
  const int *super, *pi, *px, *s;
  const double* x;
  int count;
};

// The arrays of a simplicial factor (p, i, nz, x; the diagonal first in
// each column, D's for LDL').
struct Columns {
  explicit Columns(const cholmod_factor& L)
      : p(static_cast<const int*>(L.p)), i(static_cast<const int*>(L.i)), nz(static_cast<const int*>(L.nz)),
        x(static_cast<const double*>(L.x)), n(static_cast<int>(L.n)), ll(L.is_ll != 0) {}
  const int *p, *i, *nz;
  const double* x;
  int n;
  bool ll;
};

}  // namespace

cholmod_factor* analyze_with_last(cholmod_sparse* A, const cholmod_factor& own, double own_nonzeros,
                                  const std::vector<int>& last, double max_fill_growth, cholmod_common* c) {
  const int n = static_cast<int>(own.n);
  const std::vector<char> in_last = membership(n, last);
  const int* own_perm = static_cast<const int*>(own.Perm);
  std::vector<int> perm;
  perm.reserve(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    if (!in_last[static_cast<std::size_t>(own_perm[k])]) perm.push_back(own_perm[k]);
  for (int k = 0; k < n; ++k)
    if (in_last[static_cast<std::size_t>(own_perm[k])]) perm.push_back(own_perm[k]);

  const int nmethods = c->nmethods, ordering = c->method[0].ordering, postorder = c->postorder;
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_GIVEN;
  c->postorder = 0;
  cholmod_factor* L = cholmod_analyze_p(A, perm.data(), nullptr, 0, c);
  const double nonzeros = c->lnz;
  c->nmethods = nmethods;
  c->method[0].ordering = ordering;
  c->postorder = postorder;
  if (L && (nonzeros > max_fill_growth * own_nonzeros || suffix_start(*L, last) < 0))
    cholmod_free_factor(&L, c);
  return L;
}

int suffix_start(const cholmod_factor& L, const std::vector<int>& last) {
  const int n = static_cast<int>(L.n), m = static_cast<int>(last.size());
  const std::vector<char> in_last = membership(n, last);
  const int* perm = static_cast<const int*>(L.Perm);
  for (int k = n - m; k < n; ++k)
    if (!in_last[static_cast<std::size_t>(perm[k])]) return -1;
  if (!L.is_super) return n - m;
  const Supernodes sn(L);
  return sn.super[sn.at(n - m)];
}

void suffix_forward(const cholmod_factor& L, int start, double* z) {
  if (L.is_super) {
    const Supernodes sn(L);
    Vector below;
    for (int s = sn.at(start); s < sn.count; ++s) {
      const Supernodes::Block b = sn.block(s);
      Eigen::Map<Vector> zs(z + (b.k1 - start), b.nscol);
      b.X.topRows(b.nscol).triangularView<Eigen::Lower>().solveInPlace(zs);
      below.noalias() = b.X.bottomRows(b.nsrow - b.nscol) * zs;
      for (int i = b.nscol; i < b.nsrow; ++i) z[b.rows[i] - start] -= below[i - b.nscol];
    }
    return;
  }
  const Columns col(L);
  for (int j = start; j < col.n; ++j) {
    const int p = col.p[j];
    // LL': divide before the update; LDL' (unit L, D on the diagonal): after.
    const double zj = col.ll ? z[j - start] / col.x[p] : z[j - start];
    for (int q = p + 1; q < p + col.nz[j]; ++q) z[col.i[q] - start] -= col.x[q] * zj;
    z[j - start] = col.ll ? zj : zj / col.x[p];
  }
}

void suffix_backward(const cholmod_factor& L, int start, double* z) {
  if (L.is_super) {
    const Supernodes sn(L);
    Vector below;
    for (int s = sn.count - 1, first = sn.at(start); s >= first; --s) {
      const Supernodes::Block b = sn.block(s);
      Eigen::Map<Vector> zs(z + (b.k1 - start), b.nscol);
      below.resize(b.nsrow - b.nscol);
      for (int i = b.nscol; i < b.nsrow; ++i) below[i - b.nscol] = z[b.rows[i] - start];
      zs.noalias() -= b.X.bottomRows(b.nsrow - b.nscol).transpose() * below;
      b.X.topRows(b.nscol).triangularView<Eigen::Lower>().transpose().solveInPlace(zs);
    }
    return;
  }
  const Columns col(L);
  for (int j = col.n - 1; j >= start; --j) {
    const int p = col.p[j];
    double t = z[j - start];
    for (int q = p + 1; q < p + col.nz[j]; ++q) t -= col.x[q] * z[col.i[q] - start];
    z[j - start] = col.ll ? t / col.x[p] : t;
  }
}

DenseMatrix suffix_inverse(const cholmod_factor& L, int start) {
  const int m = static_cast<int>(L.n) - start;
  // The suffix's block of the Cholesky factor, lower triangle (an LDL'
  // factor becomes L D^1/2: D > 0 for K_bar).
  DenseMatrix C = DenseMatrix::Zero(m, m);
  if (L.is_super) {
    const Supernodes sn(L);
    for (int s = sn.at(start); s < sn.count; ++s) {
      const Supernodes::Block b = sn.block(s);
      for (int j = 0; j < b.nscol; ++j)
        for (int i = j; i < b.nsrow; ++i) C(b.rows[i] - start, b.k1 + j - start) = b.X(i, j);
    }
  } else {
    const Columns col(L);
    for (int j = start; j < col.n; ++j) {
      const int p = col.p[j];
      const double scale = col.ll ? 1.0 : std::sqrt(col.x[p]);
      C(j - start, j - start) = col.ll ? col.x[p] : scale;
      for (int q = p + 1; q < p + col.nz[j]; ++q) C(col.i[q] - start, j - start) = col.x[q] * scale;
    }
  }
  int info = 0;
  dpotri_("L", &m, C.data(), &m, &info);
  C.triangularView<Eigen::StrictlyUpper>() = C.transpose();
  if (info != 0) C.setConstant(std::nan(""));  // a zero pivot: not from a factor of an SPD matrix
  return C;
}

}  // namespace railvsi

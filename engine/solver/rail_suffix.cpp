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

// The supernode whose first column is `start`.
int supernode_at(const cholmod_factor& L, int start) {
  const int* super = static_cast<const int*>(L.super);
  int s = static_cast<int>(L.nsuper);
  while (s > 0 && super[s] > start) --s;
  return s;
}

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
  return static_cast<const int*>(L.super)[supernode_at(L, n - m)];
}

void suffix_forward(const cholmod_factor& L, int start, double* z) {
  const int n = static_cast<int>(L.n);
  const double* Lx = static_cast<const double*>(L.x);
  if (L.is_super) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* Ls = static_cast<const int*>(L.s);
    Vector below;
    for (int s = supernode_at(L, start); s < static_cast<int>(L.nsuper); ++s) {
      const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s];
      const int* rows = Ls + pi[s];
      const SupernodeBlock X(Lx + px[s], nsrow, nscol, Eigen::OuterStride<>(nsrow));
      Eigen::Map<Vector> zs(z + (k1 - start), nscol);
      X.topRows(nscol).triangularView<Eigen::Lower>().solveInPlace(zs);
      below.noalias() = X.bottomRows(nsrow - nscol) * zs;
      for (int i = nscol; i < nsrow; ++i) z[rows[i] - start] -= below[i - nscol];
    }
    return;
  }
  const int* Lp = static_cast<const int*>(L.p);
  const int* Li = static_cast<const int*>(L.i);
  const int* Lnz = static_cast<const int*>(L.nz);
  for (int j = start; j < n; ++j) {
    const int p = Lp[j];
    // LL': divide before the update; LDL' (unit L, D on the diagonal): after.
    const double zj = L.is_ll ? z[j - start] / Lx[p] : z[j - start];
    for (int q = p + 1; q < p + Lnz[j]; ++q) z[Li[q] - start] -= Lx[q] * zj;
    z[j - start] = L.is_ll ? zj : zj / Lx[p];
  }
}

void suffix_backward(const cholmod_factor& L, int start, double* z) {
  const int n = static_cast<int>(L.n);
  const double* Lx = static_cast<const double*>(L.x);
  if (L.is_super) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* Ls = static_cast<const int*>(L.s);
    Vector below;
    const int first = supernode_at(L, start);
    for (int s = static_cast<int>(L.nsuper) - 1; s >= first; --s) {
      const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s];
      const int* rows = Ls + pi[s];
      const SupernodeBlock X(Lx + px[s], nsrow, nscol, Eigen::OuterStride<>(nsrow));
      Eigen::Map<Vector> zs(z + (k1 - start), nscol);
      below.resize(nsrow - nscol);
      for (int i = nscol; i < nsrow; ++i) below[i - nscol] = z[rows[i] - start];
      zs.noalias() -= X.bottomRows(nsrow - nscol).transpose() * below;
      X.topRows(nscol).triangularView<Eigen::Lower>().transpose().solveInPlace(zs);
    }
    return;
  }
  const int* Lp = static_cast<const int*>(L.p);
  const int* Li = static_cast<const int*>(L.i);
  const int* Lnz = static_cast<const int*>(L.nz);
  for (int j = n - 1; j >= start; --j) {
    const int p = Lp[j];
    double t = z[j - start];
    for (int q = p + 1; q < p + Lnz[j]; ++q) t -= Lx[q] * z[Li[q] - start];
    z[j - start] = L.is_ll ? t / Lx[p] : t;
  }
}

DenseMatrix suffix_inverse(const cholmod_factor& L, int start) {
  const int n = static_cast<int>(L.n), m = n - start;
  const double* Lx = static_cast<const double*>(L.x);
  // The suffix's block of the Cholesky factor, lower triangle (an LDL'
  // factor becomes L D^1/2: D > 0 for K_bar).
  DenseMatrix C = DenseMatrix::Zero(m, m);
  if (L.is_super) {
    const int* super = static_cast<const int*>(L.super);
    const int* pi = static_cast<const int*>(L.pi);
    const int* px = static_cast<const int*>(L.px);
    const int* Ls = static_cast<const int*>(L.s);
    for (int s = supernode_at(L, start); s < static_cast<int>(L.nsuper); ++s) {
      const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s];
      const double* X = Lx + px[s];
      for (int j = 0; j < nscol; ++j)
        for (int i = j; i < nsrow; ++i)
          C(Ls[pi[s] + i] - start, k1 + j - start) = X[i + static_cast<std::ptrdiff_t>(j) * nsrow];
    }
  } else {
    const int* Lp = static_cast<const int*>(L.p);
    const int* Li = static_cast<const int*>(L.i);
    const int* Lnz = static_cast<const int*>(L.nz);
    for (int j = start; j < n; ++j) {
      const int p = Lp[j];
      const double scale = L.is_ll ? 1.0 : std::sqrt(Lx[p]);
      C(j - start, j - start) = L.is_ll ? Lx[p] : scale;
      for (int q = p + 1; q < p + Lnz[j]; ++q) C(Li[q] - start, j - start) = Lx[q] * scale;
    }
  }
  int info = 0;
  dpotri_("L", &m, C.data(), &m, &info);
  C.triangularView<Eigen::StrictlyUpper>() = C.transpose();
  if (info != 0) C.setConstant(std::nan(""));  // a zero pivot: not from a factor of an SPD matrix
  return C;
}

}  // namespace railvsi

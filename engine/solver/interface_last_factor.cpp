#include "solver/interface_last_factor.hpp"

#include <algorithm>
#include <memory>

#include <fmt/format.h>

#include "solver/cholmod_handles.hpp"

namespace railvsi {
namespace {

// Calls f(row, column, value) for the entries of L (an L L' factor, in its
// own order) in columns [first_column, end_column) and rows >= first_row.
template <class F>
void for_each_entry(const cholmod_factor& L, int first_column, int end_column, int first_row, F&& f) {
  const auto* x = static_cast<const double*>(L.x);
  if (L.is_super) {
    const auto* super = static_cast<const int*>(L.super);
    const auto* pi = static_cast<const int*>(L.pi);
    const auto* px = static_cast<const int*>(L.px);
    const auto* rows = static_cast<const int*>(L.s);
    for (std::size_t s = 0; s < L.nsuper; ++s) {
      const int k1 = std::max(super[s], first_column), k2 = std::min(super[s + 1], end_column);
      const int height = pi[s + 1] - pi[s];
      // Column j of supernode s: `height` values from px[s] + (j - super[s]) * height,
      // rows rows[pi[s]...]; those above the diagonal are not L's (rows < j).
      for (int j = k1; j < k2; ++j)
        for (int r = 0; r < height; ++r) {
          const int i = rows[pi[s] + r];
          if (i >= first_row && i >= j) f(i, j, x[px[s] + (j - super[s]) * height + r]);
        }
    }
    return;
  }
  const auto* p = static_cast<const int*>(L.p);
  const auto* i = static_cast<const int*>(L.i);
  const auto* nz = static_cast<const int*>(L.nz);
  for (int j = first_column; j < end_column; ++j)
    for (int q = p[j]; q < p[j] + nz[j]; ++q)
      if (i[q] >= first_row) f(i[q], j, x[q]);
}

// A CHOLMOD L L' factor whose first n_interior positions are the interior
// and the rest the interface in its own order.
const cholmod_factor* interface_last(const ShiftInvertFactor& factor, int n_interior) {
  const cholmod_factor* L = factor.cholmod_l();
  if (!L || !L->is_ll || L->itype != CHOLMOD_INT || n_interior > static_cast<int>(L->n)) return nullptr;
  const auto* perm = static_cast<const int*>(L->Perm);
  for (int k = 0; k < static_cast<int>(L->n); ++k)
    if (k < n_interior ? perm[k] >= n_interior : perm[k] != k) return nullptr;
  return L;
}

}  // namespace

std::vector<int> interface_last_ordering(const SparseMatrix& K_II, int n_interface, Status& status) {
  const int n_interior = static_cast<int>(K_II.rows());
  CholmodCommon common;
  cholmod_common* c = common.get();
  cholmod_sparse view = cholmod_view_symmetric(K_II);
  // The symbolic analysis only (the ordering CHOLMOD would factor K_II in).
  const std::unique_ptr<cholmod_factor, CholmodFactorDeleter> own(cholmod_analyze(&view, c), CholmodFactorDeleter{c});
  if (!own) {
    status = {StatusCode::kDiverged, fmt::format("CHOLMOD could not order the bridge's interior of {} DOFs (status {})",
                                                 n_interior, c->status)};
    return {};
  }
  const auto* perm = static_cast<const int*>(own->Perm);
  std::vector<int> order(perm, perm + n_interior);
  for (int g = 0; g < n_interface; ++g) order.push_back(n_interior + g);
  status = Status::Ok();
  return order;
}

bool constraint_modes(const ShiftInvertFactor& factor, int n_interior, int column_block, DenseMatrix& Psi) {
  const cholmod_factor* L = interface_last(factor, n_interior);
  if (!L || column_block < 1) return false;
  const int n = static_cast<int>(L->n), n_interface = n - n_interior;
  // L_GI' (n_interior x n_interface), sparse: an interface DOF's row of L
  // reaches the interior columns on its elimination-tree paths only.
  std::vector<Triplet> t;
  for_each_entry(*L, 0, n_interior, n_interior, [&](int i, int j, double v) { t.emplace_back(j, i - n_interior, v); });
  SparseMatrix LGIt(n_interior, n_interface);
  LGIt.setFromTriplets(t.begin(), t.end());
  t.clear();
  t.shrink_to_fit();
  const auto* perm = static_cast<const int*>(L->Perm);
  Psi.resize(n_interior, n_interface);
  // L' y = [L_GI' e; 0]: y's interface part is 0, its interior part
  // L_II^-T L_GI' e (the factor's order).
  // One right-hand side and one solution array for every block (a fresh
  // allocation of this size is a page fault per 4 kB).
  DenseMatrix rhs, y;
  for (int c0 = 0; c0 < n_interface; c0 += column_block) {
    const int w = std::min(column_block, n_interface - c0);
    rhs.resize(n, w);
    rhs.setZero();
    rhs.topRows(n_interior) = LGIt.middleCols(c0, w);
    if (!factor.solve(CHOLMOD_Lt, rhs, y)) return false;
    for (int j = 0; j < w; ++j) {
      double* psi = Psi.col(c0 + j).data();
      const double* yj = y.col(j).data();
      for (int k = 0; k < n_interior; ++k) psi[perm[k]] = -yj[k];
    }
  }
  return true;
}

}  // namespace railvsi

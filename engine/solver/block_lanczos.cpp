#include "solver/block_lanczos.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "core/split_mix64.hpp"
#include "solver/dense_products.hpp"

namespace railvsi {
namespace {

using Block = Eigen::Ref<DenseMatrix>;

// The Lanczos basis V (M-orthonormal columns), M V, and the pairs found
// before (F, M F), against which every new block is orthogonalized.
struct Basis {
  const SparseMatrix& M;
  const DenseMatrix& F;
  DenseMatrix MF;
  DenseMatrix V, MV;
  Eigen::Index size = 0;  // columns of V in use
};

// W -= F (MF' W) and W -= V h with h = V' M W (h returned, summed over the
// passes: classical Gram-Schmidt, twice for a vector on its own, "twice is
// enough"). MW follows.
DenseMatrix project_out(Basis& b, Block W, Block MW, int passes = 2) {
  DenseMatrix h = DenseMatrix::Zero(b.size, W.cols()), c, hp;
  for (int pass = 0; pass < passes; ++pass) {
    if (b.F.cols() > 0) {
      c.resize(b.F.cols(), W.cols());
      multiply_blocks(true, b.MF, W, c);
      multiply_blocks(false, b.F, c, W, -1.0, 1.0);
      multiply_blocks(false, b.MF, c, MW, -1.0, 1.0);
    }
    if (b.size == 0) continue;
    hp.resize(b.size, W.cols());
    multiply_blocks(true, b.MV.leftCols(b.size), W, hp);
    multiply_blocks(false, b.V.leftCols(b.size), hp, W, -1.0, 1.0);
    multiply_blocks(false, b.MV.leftCols(b.size), hp, MW, -1.0, 1.0);
    h += hp;
  }
  return h;
}

// M-orthonormalizes the columns of W (already M-orthogonal to F and V)
// among themselves, keeping `width` columns: W_in = W_out R with R of
// `width` rows (upper triangular when W has full rank). Cholesky QR twice
// (BLAS-3). A block that is (nearly) rank deficient (the Krylov space
// nearly invariant, or the end of the space) goes column by column instead:
// a column that vanishes is dropped, and the block is filled up with
// random columns orthogonal to everything (rows of R zero) while the space
// has room; `width` is then the columns kept, W's first ones.
DenseMatrix orthonormalize(Basis& b, DenseMatrix& W, DenseMatrix& MW, Eigen::Index room, SplitMix64& random) {
  const Eigen::Index w = W.cols();
  DenseMatrix R = DenseMatrix::Identity(w, w), G(w, w);
  bool cholesky = w <= room;
  for (int pass = 0; pass < 2 && cholesky; ++pass) {
    multiply_blocks(true, W, MW, G);
    G = (0.5 * (G + G.transpose())).eval();
    Eigen::LLT<DenseMatrix> llt(G);
    if (llt.info() != Eigen::Success) {
      cholesky = false;
      break;
    }
    const DenseMatrix U = llt.matrixU();
    const Eigen::VectorXd d = U.diagonal().cwiseAbs();
    // A condition number of W over 1e6 loses more orthogonality than a
    // second pass restores.
    if (!(d.minCoeff() > 1e-6 * d.maxCoeff())) {
      cholesky = false;
      break;
    }
    U.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(W);
    U.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(MW);
    R = (U * R).eval();
  }
  if (cholesky) return R;
  // Column by column (modified Gram-Schmidt in the M inner product, twice
  // per column) on W and MW as they are now (W_in R^-1, M W_in R^-1).
  const Eigen::Index n = W.rows();
  DenseMatrix S = DenseMatrix::Zero(w, w);  // W_now = W_out S, rows of the kept columns
  double largest = 0.0;
  for (Eigen::Index i = 0; i < w; ++i) largest = std::max(largest, W.col(i).dot(MW.col(i)));
  largest = std::sqrt(largest);
  Eigen::Index kept = 0;
  const auto against_kept = [&](Eigen::Index i, double* coefficients) {
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index k = 0; k < kept; ++k) {
        const double r = MW.col(k).dot(W.col(i));
        W.col(i) -= r * W.col(k);
        MW.col(i) -= r * MW.col(k);
        if (coefficients) coefficients[k] += r;
      }
  };
  for (Eigen::Index i = 0; i < w && kept < room; ++i) {
    Vector coefficients = Vector::Zero(w);
    against_kept(i, coefficients.data());
    const double norm = std::sqrt(std::max(W.col(i).dot(MW.col(i)), 0.0));
    // Rounding of a column inside the span: dropped.
    if (!(norm > 1e-12 * largest)) continue;
    W.col(kept) = W.col(i) / norm;
    MW.col(kept) = MW.col(i) / norm;
    S.row(kept) = Eigen::RowVectorXd::Zero(w);
    S.block(0, i, kept, 1) = coefficients.head(kept);
    S(kept, i) = norm;
    ++kept;
  }
  // Fill up with random directions while the space has room.
  const Eigen::Index wanted = std::min(w, room);
  for (int attempt = 0; kept < wanted && attempt < 3 * w; ++attempt) {
    const Eigen::Index i = kept;
    for (Eigen::Index r = 0; r < n; ++r) W(r, i) = random.next_unit() - 0.5;
    MW.col(i) = b.M * W.col(i);
    const double before = std::sqrt(W.col(i).dot(MW.col(i)));
    project_out(b, W.col(i), MW.col(i));
    against_kept(i, nullptr);
    const double norm = std::sqrt(std::max(W.col(i).dot(MW.col(i)), 0.0));
    if (!(norm > 1e-6 * before)) continue;
    W.col(i) /= norm;
    MW.col(i) /= norm;
    S.row(i).setZero();
    ++kept;
  }
  W.conservativeResize(Eigen::NoChange, kept);
  MW.conservativeResize(Eigen::NoChange, kept);
  return S.topRows(kept) * R;
}

// W (and MW = M W) M-orthogonal to F and V, then M-orthonormal: twice
// (one Gram-Schmidt pass against the basis, then within the block: block
// classical Gram-Schmidt twice, BCGS2), since a block whose columns differ
// in size by orders (nearly converged directions) amplifies in its second
// step the rounding left along the basis in the first. Each round's single
// pass is enough there: the second round's removes what the first's
// normalization amplified (two passes per round cost 25.5 s of the 53 s at
// seed scale, docs/performance.md). W_in = V h + W_out R; h added to `h`
// when given.
DenseMatrix extend(Basis& b, DenseMatrix& W, DenseMatrix& MW, Eigen::Index room, SplitMix64& random,
                   DenseMatrix* h) {
  DenseMatrix h1 = project_out(b, W, MW, 1);
  const DenseMatrix R1 = orthonormalize(b, W, MW, room, random);
  const DenseMatrix h2 = project_out(b, W, MW, 1);
  const DenseMatrix R2 = orthonormalize(b, W, MW, room, random);
  if (h) *h = h1 + h2 * R1;
  return R2 * R1;
}

}  // namespace

NearestPairs BlockLanczos::nearest(const SparseMatrix& M, const ShiftInvertFactor& factor, Eigen::Index count,
                                   const DenseMatrix& found, int max_restarts) const {
  NearestPairs out;
  const Eigen::Index n = M.rows();
  const Eigen::Index dims = n - found.cols();  // the operator's range
  count = std::min(count, dims);
  if (count < 1) return out;
  const Eigen::Index block = std::min<Eigen::Index>(std::max(block_, 1), dims);
  // Twice the pairs wanted, and three blocks beyond them: the wanted ones
  // then converge in a basis that fits, restarted rarely.
  const Eigen::Index cap = std::min(dims, std::max(2 * count, count + 3 * block));
  // A thick restart keeps the wanted pairs and half the rest.
  const Eigen::Index keep = std::max(count, std::min(count + (cap - count) / 2, cap - block));

  Basis b{M, found, M * found, DenseMatrix(n, cap), DenseMatrix(n, cap)};
  SplitMix64 random(0x5eed + static_cast<std::uint64_t>(found.cols()));
  // The start: a fixed pseudo-random block (the same modes to the last bit
  // on every run).
  Eigen::Index width = block;
  for (Eigen::Index j = 0; j < width; ++j)
    for (Eigen::Index i = 0; i < n; ++i) b.V(i, j) = random.next_unit() - 0.5;
  b.MV.leftCols(width) = sparse_times_dense(M, b.V.leftCols(width));
  {
    DenseMatrix V0 = b.V.leftCols(width), MV0 = b.MV.leftCols(width);
    extend(b, V0, MV0, dims, random, nullptr);
    width = V0.cols();
    b.V.leftCols(width) = V0;
    b.MV.leftCols(width) = MV0;
  }
  b.size = width;

  // H = V' M OP V, the projected operator (symmetric in the M inner product).
  DenseMatrix H = DenseMatrix::Zero(cap, cap);
  Eigen::Index last = 0;  // the block the next step expands
  DenseMatrix W, MW, Hs, X;
  Eigen::SelfAdjointEigenSolver<DenseMatrix> ritz;
  const double floor = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
  int restarts = 0;
  for (;;) {
    ++out.iterations;
    // One solve for the block: W = (K - sigma M)^-1 M V_last.
    const DenseMatrix rhs = b.MV.middleCols(last, width);
    if (!factor.solve(rhs, W) || !W.allFinite()) {
      out.status = {StatusCode::kDiverged, fmt::format("the solve with K - sigma M (sigma = {:.6g}) failed", factor.sigma())};
      return out;
    }
    MW = sparse_times_dense(M, W);
    DenseMatrix h;
    // The next block and its coupling: OP V = V H + W_next R E_last'.
    const DenseMatrix coupling = extend(b, W, MW, dims - b.size, random, &h);
    H.block(0, last, b.size, width) = h;
    H.block(last, 0, width, b.size) = h.transpose();
    const Eigen::Index next = W.cols();

    // Rayleigh-Ritz: the pairs nearest the shift are the largest |theta|.
    Hs = H.topLeftCorner(b.size, b.size);
    Hs = (0.5 * (Hs + Hs.transpose())).eval();
    ritz.compute(Hs);
    if (ritz.info() != Eigen::Success) {
      out.status = {StatusCode::kNoConvergence, "the projected eigenproblem of block Lanczos failed"};
      return out;
    }
    const Eigen::VectorXd& theta = ritz.eigenvalues();
    const DenseMatrix& Y = ritz.eigenvectors();
    std::vector<Eigen::Index> order(static_cast<std::size_t>(b.size));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](Eigen::Index i, Eigen::Index j) { return std::abs(theta[i]) > std::abs(theta[j]); });
    bool converged = b.size >= count;
    for (Eigen::Index k = 0; converged && k < count; ++k) {
      const Eigen::Index i = order[static_cast<std::size_t>(k)];
      const double residual = (coupling * Y.block(last, i, width, 1)).norm();
      converged = residual <= tolerance_ * std::max(floor, std::abs(theta[i]));
    }
    if (converged) {
      // The wanted pairs, ascending in lambda = sigma + 1 / theta (as
      // Spectra's backend gives them).
      std::vector<Eigen::Index> wanted(order.begin(), order.begin() + count);
      const auto lambda_of = [&](Eigen::Index i) { return factor.sigma() + 1.0 / theta[i]; };
      std::stable_sort(wanted.begin(), wanted.end(),
                       [&](Eigen::Index i, Eigen::Index j) { return lambda_of(i) < lambda_of(j); });
      DenseMatrix Ysel(b.size, count);
      for (Eigen::Index k = 0; k < count; ++k) Ysel.col(k) = Y.col(wanted[static_cast<std::size_t>(k)]);
      out.phi.resize(n, count);
      multiply_blocks(false, b.V.leftCols(b.size), Ysel, out.phi);
      DenseMatrix MX(n, count);
      multiply_blocks(false, b.MV.leftCols(b.size), Ysel, MX);
      for (Eigen::Index k = 0; k < count; ++k) {
        out.lambda.push_back(lambda_of(wanted[static_cast<std::size_t>(k)]));
        out.phi.col(k) /= std::sqrt(out.phi.col(k).dot(MX.col(k)));
      }
      return out;
    }
    if (next == 0) {  // not reached: an invariant space has residual zero above
      out.status = {StatusCode::kNoConvergence, "block Lanczos found no direction to extend its basis"};
      return out;
    }
    if (b.size + next <= cap) {
      // Grow: the next block joins the basis.
      b.V.middleCols(b.size, next) = W;
      b.MV.middleCols(b.size, next) = MW;
      H.block(b.size, last, next, width) = coupling;
      H.block(last, b.size, width, next) = coupling.transpose();
      last = b.size;
      b.size += next;
      width = next;
      continue;
    }
    // Thick restart: the `keep` Ritz vectors nearest the shift and the next
    // block; H becomes diag(theta) coupled to that block by R Y_last.
    if (++restarts > max_restarts) {
      out.status = {StatusCode::kNoConvergence,
                    fmt::format("block Lanczos did not converge the {} eigenpairs nearest {:.6g} rad^2/s^2 in {} "
                                "restarts",
                                count, factor.sigma(), max_restarts)};
      return out;
    }
    DenseMatrix Ykeep(b.size, keep);
    for (Eigen::Index k = 0; k < keep; ++k) Ykeep.col(k) = Y.col(order[static_cast<std::size_t>(k)]);
    X.resize(n, keep);
    multiply_blocks(false, b.V.leftCols(b.size), Ykeep, X);
    b.V.leftCols(keep) = X;
    multiply_blocks(false, b.MV.leftCols(b.size), Ykeep, X);
    b.MV.leftCols(keep) = X;
    const DenseMatrix tail = coupling * Ykeep.middleRows(last, width);
    H.setZero();
    for (Eigen::Index k = 0; k < keep; ++k) H(k, k) = theta[order[static_cast<std::size_t>(k)]];
    b.V.middleCols(keep, next) = W;
    b.MV.middleCols(keep, next) = MW;
    H.block(keep, 0, next, keep) = tail;
    H.block(0, keep, keep, next) = tail.transpose();
    b.size = keep + next;
    last = keep;
    width = next;
  }
}

}  // namespace railvsi

#include "solver/modal_analysis.hpp"

#include <limits>
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include <fmt/format.h>

#include "solver/lanczos_slices.hpp"
#include "solver/shift_invert_factor.hpp"
#include "solver/subspace_iteration.hpp"

namespace railvsi {
namespace {

// Up to this size, more than half of the modes are solved densely: a
// Lanczos slice cannot take the last mode of a model (its basis, M-orthogonal
// to the modes found, has no room for one more vector).
constexpr Eigen::Index kDenseFromDofs = 3000;

// Eigen's dense solver on M x = mu (K - sigma M) x, mu = 1 / (lambda - sigma)
// (K - sigma M positive definite): its error is rounding relative to the
// largest mu, the lowest mode's, so the low modes come out to rounding.
ModalResult dense_modes(const SparseMatrix& K, const SparseMatrix& M, Eigen::Index wanted,
                        const ModalOptions& options) {
  ModalResult result;
  result.solver = ModeSolver::kLanczos;  // (not subspace iteration)
  const double sigma = options.shift_rad2_per_s2;
  const DenseMatrix A = DenseMatrix(K) - sigma * DenseMatrix(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> dense(DenseMatrix(M), A);
  if (dense.info() != Eigen::Success) {
    result.status = {StatusCode::kDiverged,
                     fmt::format("K - sigma M (sigma = {} rad^2/s^2) is not positive definite: a mechanism, or an "
                                 "eigenvalue below the shift",
                                 sigma)};
    return result;
  }
  const Eigen::Index n = K.rows();
  wanted = std::min(wanted, n);
  result.shapes.resize(n, wanted);
  for (Eigen::Index k = 0; k < wanted; ++k) {
    const Eigen::Index j = n - 1 - k;  // mu ascending: the largest first
    const double lambda = sigma + 1.0 / dense.eigenvalues()[j];
    result.frequencies_hz.push_back(std::sqrt(std::max(lambda, 0.0)) / (2.0 * std::numbers::pi));
    auto phi = result.shapes.col(k);
    phi = dense.eigenvectors().col(j);
    phi /= std::sqrt(phi.dot(M * phi));
    Eigen::Index at = 0;
    phi.cwiseAbs().maxCoeff(&at);
    if (phi[at] < 0.0) phi = -phi;
  }
  result.factorizations = 1;
  return result;
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The largest |K phi - w^2 M phi| / |K phi| of the pairs; infinity when one
// is not finite.
double max_relative_residual(const SparseMatrix& K, const SparseMatrix& M, const ModalResult& r) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < r.shapes.cols(); ++k) {
    const Eigen::VectorXd Kphi = K * r.shapes.col(k);
    const double w = 2.0 * std::numbers::pi * r.frequencies_hz[static_cast<std::size_t>(k)];
    const double norm = Kphi.norm();
    const double residual = (Kphi - w * w * (M * r.shapes.col(k))).norm();
    const double relative = norm > 0.0 ? residual / norm : residual;
    if (!std::isfinite(relative)) return kInfinity;
    worst = std::max(worst, relative);
  }
  return worst;
}

}  // namespace

ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options,
                           const ShiftInvertFactor* first_factor) {
  ModalResult result;
  const Eigen::Index n = K.rows();
  const bool cut = options.max_frequency_hz > 0.0;
  const Eigen::Index nev = std::min<Eigen::Index>(std::max(options.modes, 0), n - 1);
  if (nev < 1 && !(cut && n > 1)) {
    result.status = {StatusCode::kInvalidInput,
                     fmt::format("cannot compute {} modes of a model with {} DOFs", options.modes, n)};
    return result;
  }
  // A small model's count up to the cut-off first (one more factor): most
  // of its modes are solved densely.
  Eigen::Index wanted = nev;
  if (cut && (options.solver == ModeSolver::kSubspace || n <= kDenseFromDofs)) {
    Status counted;
    const Eigen::Index below = count_modes_below(K, M, options.max_frequency_hz, &counted, options.indefinite);
    if (!counted.ok()) {
      result.status = counted;
      return result;
    }
    wanted = std::max(wanted, below);
  }
  if (n <= kDenseFromDofs && 2 * wanted > n) return dense_modes(K, M, wanted, options);
  if (options.solver != ModeSolver::kSubspace) {
    ModalResult block = lanczos_slices(K, M, nev, options, first_factor);
    if (options.lanczos_block <= 1) return block;
    block.block_residual = block.status.ok() ? max_relative_residual(K, M, block) : kInfinity;
    block.max_residual = block.block_residual;
    if (block.block_residual <= kMaxBlockLanczosResidual) return block;
    ModalOptions single = options;
    single.lanczos_block = 1;
    ModalResult r = lanczos_slices(K, M, nev, single, first_factor);
    r.factorizations += block.factorizations;
    r.factor_cpu_s += block.factor_cpu_s;
    r.block_residual = block.block_residual;
    r.block_fallback = true;
    r.max_residual = r.status.ok() ? max_relative_residual(K, M, r) : kInfinity;
    return r;
  }

  // Subspace iteration has one shift: its count comes from the Sturm count.
  wanted = std::min(wanted, n - 1);
  result.solver = ModeSolver::kSubspace;
  if (wanted < 1) return result;  // no mode up to the cut-off, none asked
  ShiftInvertFactor factor(K, M);
  if (!factor.factorize(options.shift_rad2_per_s2).ok()) {
    result.status = factor.status();
    return result;
  }
  result = subspace_iteration(K, M, wanted, factor, options);
  result.solver = ModeSolver::kSubspace;
  result.factorizations = cut ? 2 : 1;
  return result;
}

ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options) {
  return modal_analysis(structure.K(), structure.M(), options);
}

}  // namespace railvsi

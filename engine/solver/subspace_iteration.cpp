#include "solver/subspace_iteration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "core/split_mix64.hpp"

namespace railvsi {

ModalResult subspace_iteration(const SparseMatrix& K, const SparseMatrix& M, Eigen::Index modes,
                               const ShiftInvertFactor& factor, const ModalOptions& options) {
  ModalResult result;
  const Eigen::Index n = K.rows();
  // Twice the wanted modes (at least 8 more): the slowest wanted mode then
  // converges by (lambda_m - sigma) / (lambda_p+1 - sigma) per iteration.
  const Eigen::Index p = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * modes, modes + 8));

  // A fixed pseudo-random start: the same modes (to the last bit) on every
  // run, and no wanted mode orthogonal to the start block.
  SplitMix64 random(0x5eed);
  DenseMatrix MX;
  {
    DenseMatrix X(n, p);
    for (Eigen::Index j = 0; j < p; ++j)
      for (Eigen::Index i = 0; i < n; ++i) X(i, j) = random.next_unit() - 0.5;
    MX.noalias() = M * X;
  }

  // K Y = M X + sigma M Y, since (K - sigma M) Y = M X: one sparse product
  // an iteration, and X itself is formed only at the end.
  const double sigma = options.shift_rad2_per_s2;
  DenseMatrix Y, MY, KXm;
  DenseMatrix Kp = DenseMatrix::Zero(p, p), Mp = DenseMatrix::Zero(p, p);  // lower halves written
  Eigen::LLT<DenseMatrix> mass_factor;
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> projected;
  // The worst residual of each iteration, to see a hopeless iteration early.
  std::vector<double> worst_of;
  constexpr int kRateWindow = 10;
  const auto fail = [&](int iteration, std::string why) {
    result.status = {StatusCode::kNoConvergence, std::move(why)};
    result.iterations = iteration;
    return result;
  };
  for (int iteration = 1; iteration <= options.max_subspace_iterations; ++iteration) {
    if (!factor.solve(MX, Y)) return fail(iteration, "the solve with K - sigma M failed");
    MY.noalias() = M * Y;
    // Both projections are symmetric: the lower halves are what the
    // eigensolver reads.
    Mp.triangularView<Eigen::Lower>() = Y.transpose() * MY;
    Kp.triangularView<Eigen::Lower>() = Y.transpose() * MX;
    Kp.triangularView<Eigen::Lower>() += sigma * Mp;
    // Eigen's generalized solver does not report a projected mass that is
    // not positive definite (a block that lost its independence): checked
    // here on its own Cholesky factor.
    mass_factor.compute(Mp);
    if (mass_factor.info() != Eigen::Success)
      return fail(iteration, fmt::format("the block of {} vectors lost its independence at iteration {}", p, iteration));
    projected.compute(Kp, Mp, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (projected.info() != Eigen::Success)
      return fail(iteration, fmt::format("the projected eigenproblem failed at iteration {}", iteration));
    const DenseMatrix& Q = projected.eigenvectors();  // ascending, Q' Mp Q = I
    const Vector& lambda = projected.eigenvalues();
    KXm.noalias() = MX * Q.leftCols(modes);  // K X = (M X_old + sigma M Y) Q
    MX.noalias() = MY * Q;
    KXm += sigma * MX.leftCols(modes);
    // Relative to |(K - sigma M) phi|, which a rigid-body mode (K phi = 0)
    // does not make zero.
    const auto largest_residual = [&](const DenseMatrix& KX) {
      double worst = 0.0;
      for (Eigen::Index k = 0; k < modes; ++k) {
        const double scale = (KX.col(k) - sigma * MX.col(k)).norm();
        const double r = (KX.col(k) - lambda[k] * MX.col(k)).norm() / std::max(scale, 1e-300);
        if (!std::isfinite(r)) return r;
        worst = std::max(worst, r);
      }
      return worst;
    };
    const double worst = largest_residual(KXm);
    if (!std::isfinite(worst)) return fail(iteration, fmt::format("a non-finite residual at iteration {}", iteration));
    if (worst <= options.subspace_tolerance) {
      // The residual above takes the solve as exact; the shapes' own, with
      // K itself, decides.
      DenseMatrix X = Y * Q.leftCols(modes);  // M-orthonormal
      if (largest_residual(K * X) <= options.subspace_tolerance) {
        result.shapes = std::move(X);
        for (Eigen::Index k = 0; k < modes; ++k)
          result.frequencies_hz.push_back(std::sqrt(std::max(lambda[k], 0.0)) / (2.0 * std::numbers::pi));
        result.iterations = iteration;
        return result;
      }
    }
    // The rate of the last kRateWindow iterations, extrapolated: stop as
    // soon as it cannot reach the tolerance within the budget (judged from
    // the second window on: a group of modes reordering in the block can
    // stall one window).
    worst_of.push_back(worst);
    if (iteration >= 2 * kRateWindow) {
      const double rate = std::pow(worst / worst_of[static_cast<std::size_t>(iteration - 1 - kRateWindow)],
                                   1.0 / kRateWindow);
      const double needed = rate < 1.0 ? std::log(options.subspace_tolerance / worst) / std::log(rate)
                                       : std::numeric_limits<double>::infinity();
      if (iteration + needed > options.max_subspace_iterations)
        return fail(iteration, fmt::format("subspace iteration would not converge in {} iterations (block of {} "
                                           "vectors; residual {:.1e} after {}, falling by {:.3f} an iteration)",
                                           options.max_subspace_iterations, p, worst, iteration, rate));
    }
  }
  return fail(options.max_subspace_iterations,
              fmt::format("subspace iteration did not converge in {} iterations (block of {} vectors)",
                          options.max_subspace_iterations, p));
}

}  // namespace railvsi

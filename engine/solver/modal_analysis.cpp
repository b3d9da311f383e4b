#include "solver/modal_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include "solver/shift_invert_factor.hpp"
#include "solver/subspace_iteration.hpp"

namespace railvsi {
namespace {

// Spectra's shift-invert operator on the factor. Spectra sets the shift in
// the solver's constructor; the factor keeps a failure as its Status, which
// is checked before the iteration starts.
class SpectraShiftInvert {
 public:
  using Scalar = double;
  explicit SpectraShiftInvert(ShiftInvertFactor& factor) : factor_(factor) {}
  Eigen::Index rows() const { return factor_.rows(); }
  Eigen::Index cols() const { return factor_.rows(); }
  void set_shift(double sigma) { factor_.factorize(sigma); }
  void perform_op(const double* x, double* y) const { factor_.solve(x, y); }  // NaN: Spectra fails to converge

 private:
  ShiftInvertFactor& factor_;
};

// max_restarts: Spectra's iterations (implicit restarts) per attempt;
// retry: double the eigenpairs after a miss (up to max_lanczos_pairs).
ModalResult lanczos(const SparseMatrix& M, Eigen::Index nev, ShiftInvertFactor& factor, const ModalOptions& options,
                    int max_restarts, bool retry) {
  ModalResult result;
  const Eigen::Index n = M.rows();
  SpectraShiftInvert op(factor);
  Spectra::SparseSymMatProd<double> mass(M);
  // A track on embankments has hundreds of nearly equal sleeper-on-ballast
  // modes. Lanczos converges slowly when the edge of the wanted set falls
  // into such a cluster: more eigenpairs than asked (and a basis twice as
  // large) converge much faster, and a miss is retried with twice as many.
  Eigen::Index wanted = std::min<Eigen::Index>(n - 1, std::max<Eigen::Index>(2 * nev, options.min_lanczos_pairs));
  for (;;) {
    const Eigen::Index ncv = std::min<Eigen::Index>(n, 2 * wanted + 1);
    Spectra::SymGEigsShiftSolver<SpectraShiftInvert, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(op, mass, wanted, ncv, options.shift_rad2_per_s2);
    if (!factor.status().ok()) {
      result.status = factor.status();
      return result;
    }
    solver.init();
    // Largest |1/(lambda - sigma)| are the eigenvalues nearest the shift;
    // reported in ascending lambda.
    solver.compute(Spectra::SortRule::LargestMagn, max_restarts, options.lanczos_tolerance,
                   Spectra::SortRule::SmallestAlge);
    if (solver.info() == Spectra::CompInfo::Successful) {
      const Vector lambda = solver.eigenvalues().head(nev);
      result.shapes = solver.eigenvectors().leftCols(nev);
      for (Eigen::Index k = 0; k < nev; ++k) {
        // A rigid-body mode comes out as a tiny negative lambda: frequency 0.
        result.frequencies_hz.push_back(std::sqrt(std::max(lambda[k], 0.0)) / (2.0 * std::numbers::pi));
        auto phi = result.shapes.col(k);
        phi /= std::sqrt(phi.dot(M * phi));
      }
      return result;
    }
    if (!retry || wanted >= std::min<Eigen::Index>(n - 1, options.max_lanczos_pairs)) break;
    wanted = std::min<Eigen::Index>({n - 1, 2 * wanted, options.max_lanczos_pairs});
  }
  result.status = {StatusCode::kNoConvergence,
                   fmt::format("the eigenvalue iteration did not converge ({} iterations with up to {} eigenpairs)",
                               max_restarts, wanted)};
  return result;
}

}  // namespace

ModalResult modal_analysis(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& options) {
  ModalResult result;
  const Eigen::Index n = K.rows();
  const Eigen::Index nev = std::min<Eigen::Index>(options.modes, n - 1);
  if (nev < 1) {
    result.status = {StatusCode::kInvalidInput,
                     fmt::format("cannot compute {} modes of a model with {} DOFs", options.modes, n)};
    return result;
  }
  ShiftInvertFactor factor(K, M);
  const auto full_lanczos = [&] { return lanczos(M, nev, factor, options, options.lanczos_max_restarts, true); };
  const auto subspace = [&] {
    ModalResult r;
    if (factor.factorize(options.shift_rad2_per_s2).ok()) r = subspace_iteration(K, M, nev, factor, options);
    else r.status = factor.status();
    r.solver = ModeSolver::kSubspace;
    return r;
  };
  switch (options.solver) {
    case ModeSolver::kLanczos:
      return full_lanczos();
    case ModeSolver::kSubspace:
      return subspace();
    case ModeSolver::kAuto:
      break;
  }
  // Each method has structures it is slow on (see ModeSolver): the other
  // one is tried when the first misses, and Lanczos without a budget last.
  // A factor that fails is not retried: neither method can do without it.
  // A final failure says why each attempt failed.
  std::string missed;
  const auto attempt = [&](ModalResult r) {
    if (!r.status.ok() && factor.status().ok()) {
      missed += (missed.empty() ? "" : "; ") + r.status.message();
      r.status = {r.status.code(), missed};
    }
    return r;
  };
  const auto done = [&](const ModalResult& r) { return r.status.ok() || !factor.status().ok(); };
  if (n >= options.subspace_from_dofs) {
    ModalResult r = attempt(subspace());
    return done(r) ? r : attempt(full_lanczos());
  }
  ModalResult r = attempt(lanczos(M, nev, factor, options, options.auto_lanczos_restarts, false));
  if (done(r)) return r;
  r = attempt(subspace());
  return done(r) ? r : attempt(full_lanczos());
}

ModalResult modal_analysis(const StructureModel& structure, const ModalOptions& options) {
  return modal_analysis(structure.K(), structure.M(), options);
}

}  // namespace railvsi

#include "solver/lanczos_slices.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/thread_cpu_time.hpp"
#include "solver/nearest_eigenpairs.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {
namespace {

double eigenvalue_of(double frequency_hz) { return std::pow(2.0 * std::numbers::pi * frequency_hz, 2); }

using Pairs = NearestPairs;

// The pairs of p above `sigma`.
Pairs above(const Pairs& p, double sigma) {
  Pairs out;
  std::vector<Eigen::Index> keep;
  for (std::size_t k = 0; k < p.lambda.size(); ++k)
    if (p.lambda[k] > sigma) keep.push_back(static_cast<Eigen::Index>(k));
  out.phi.resize(p.phi.rows(), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    out.lambda.push_back(p.lambda[static_cast<std::size_t>(keep[j])]);
    out.phi.col(static_cast<Eigen::Index>(j)) = p.phi.col(keep[j]);
  }
  return out;
}

// Appends the pairs of b to a (both ascending in lambda) and sorts.
void merge(Pairs& a, const Pairs& b) {
  std::vector<double> lambda = a.lambda;
  lambda.insert(lambda.end(), b.lambda.begin(), b.lambda.end());
  DenseMatrix phi(a.phi.rows(), static_cast<Eigen::Index>(lambda.size()));
  phi << a.phi, b.phi;
  std::vector<Eigen::Index> order(lambda.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return lambda[i] < lambda[j]; });
  a.lambda.clear();
  a.phi.resize(phi.rows(), phi.cols());
  for (std::size_t j = 0; j < order.size(); ++j) {
    a.lambda.push_back(lambda[static_cast<std::size_t>(order[j])]);
    a.phi.col(static_cast<Eigen::Index>(j)) = phi.col(order[j]);
  }
}

// Where the next shift goes: in the widest relative gap between
// consecutive points (the shift, then the slice's eigenvalues), from the
// gap after point `first` on. Returns the index i of the gap (p_i, p_i+1),
// none when every gap there is below 1e-6 (a group of equal modes, to
// rounding: the L D L' factor's inertia would be rounding there).
std::optional<std::size_t> widest_gap(const std::vector<double>& points, std::size_t first) {
  constexpr double kNarrowest = 1e-6;
  std::optional<std::size_t> best;
  double widest = kNarrowest;
  for (std::size_t i = first; i + 1 < points.size(); ++i) {
    const double gap = (points[i + 1] - points[i]) / (std::abs(points[i + 1]) + std::abs(points[i]));
    if (gap > widest) {
      widest = gap;
      best = i;
    }
  }
  return best;
}

}  // namespace

ModalResult lanczos_slices(const SparseMatrix& K, const SparseMatrix& M, Eigen::Index modes,
                           const ModalOptions& options, const ShiftInvertFactor* first) {
  ModalResult result;
  result.solver = ModeSolver::kLanczos;
  const Eigen::Index n = K.rows();
  modes = std::min(modes, n - 1);
  const bool cut = options.max_frequency_hz > 0.0;
  const double lambda_cut = cut ? eigenvalue_of(options.max_frequency_hz) : 0.0;
  const Eigen::Index per_slice = std::max(2, options.slice_modes);

  // The first shift lies below the spectrum (its L L' factor proves it);
  // the next ones inside, each factorized once as L D L'.
  // `here` is `first` or `owned`; the factor of the next shift reuses the
  // storage (and MUMPS's ordering) of the one before.
  std::unique_ptr<ShiftInvertFactor> owned;
  auto next = std::make_unique<ShiftInvertFactor>(K, M, options.indefinite);
  const ShiftInvertFactor* here = first;
  double cpu_s = thread_cpu_s();
  if (!here) {
    owned = std::make_unique<ShiftInvertFactor>(K, M, options.indefinite);
    if (!owned->factorize(options.shift_rad2_per_s2).ok()) {
      result.status = owned->status();
      return result;
    }
    here = owned.get();
    result.factorizations = 1;
  }
  result.factor_cpu_s += thread_cpu_s() - cpu_s;
  const std::unique_ptr<NearestEigenpairs> solver = make_nearest_eigenpairs(options);
  Pairs all;  // every pair accepted
  all.phi.resize(n, 0);
  // Counted already: one slice of exactly the count, certified when every
  // pair lies below the cut-off.
  bool certified_by_count = false;
  if (cut && options.modes_below_cutoff >= 0 && modes <= options.modes_below_cutoff &&
      here->eigenvalues_below() == 0) {
    const Eigen::Index count = std::min<Eigen::Index>(options.modes_below_cutoff, n - 1);
    Pairs near = count > 0 ? solver->nearest(M, *here, count, all.phi, options.slice_restarts) : Pairs{};
    result.iterations += near.iterations;
    certified_by_count =
        near.status.ok() && static_cast<Eigen::Index>(near.lambda.size()) == count &&
        std::all_of(near.lambda.begin(), near.lambda.end(), [&](double l) { return l > here->sigma() && l < lambda_cut; });
    if (certified_by_count && count > 0) merge(all, near);
  }
  Eigen::Index grow = 1;  // a slice without a gap to put the next shift in is asked again, twice as wide
  Eigen::Index shrink = 1;  // one that does not converge in slice_restarts, half as wide
  bool wide = false;
  while (!certified_by_count) {
    const Eigen::Index certified = static_cast<Eigen::Index>(all.lambda.size());
    const Eigen::Index remaining = modes - certified;
    // A quarter more than the modes still wanted, so that the last shift
    // finds a gap after them.
    // A slice that converges neither at its size nor at 2 modes is asked
    // once more as the one-shift solvers did, with four times its modes and
    // every restart allowed (a cluster of hundreds of nearly equal ones).
    const Eigen::Index ask =
        wide ? 4 * per_slice
             : std::max<Eigen::Index>(
                   2, grow * (cut ? per_slice : std::min(per_slice, remaining + std::max<Eigen::Index>(4, remaining / 4))) /
                          shrink);
    // The modes found below the shift are deflated: else the nearest ones
    // would converge again (most of them, below a shift at the top of a
    // dense band).
    Pairs near = solver->nearest(M, *here, std::min(ask, n - 1 - all.phi.cols()), all.phi,
                                 wide ? options.lanczos_max_restarts : options.slice_restarts);
    result.iterations += near.iterations;
    if (!near.status.ok()) {
      if (wide) {
        result.status = near.status;
        return result;
      }
      // The slice's edge fell inside a group of nearly equal modes (the
      // track's rail-on-pad modes agree to 1e-7): half as many modes, so
      // that the next shift comes closer to the group and spreads it.
      if (ask == 2) wide = true;
      shrink *= 2;
      continue;
    }
    Pairs slice = above(near, here->sigma());
    const auto found = static_cast<Eigen::Index>(slice.lambda.size());
    if (found == n - here->eigenvalues_below()) {  // every eigenvalue above the shift: nothing left to certify
      merge(all, slice);
      break;
    }
    // The next shift: past every mode still wanted and past the cut-off
    // when this slice reaches both, else in the widest gap of its top third
    // (of the whole slice when that third is one group of equal modes).
    std::vector<double> points{here->sigma()};
    points.insert(points.end(), slice.lambda.begin(), slice.lambda.end());
    const auto below_cut = static_cast<Eigen::Index>(
        std::count_if(slice.lambda.begin(), slice.lambda.end(), [&](double l) { return l <= lambda_cut; }));
    const Eigen::Index last_needed = std::max(remaining, cut ? below_cut : 0);
    std::optional<std::size_t> gap;
    bool last = last_needed < found && (!cut || slice.lambda.back() > lambda_cut);
    if (last) gap = widest_gap(points, static_cast<std::size_t>(std::max<Eigen::Index>(last_needed, 0)));
    last = last && gap.has_value();
    if (!last) gap = widest_gap(points, static_cast<std::size_t>(std::max<Eigen::Index>(1, (2 * found) / 3)));
    if (!last && !gap) gap = widest_gap(points, 1);
    if (!gap) {
      if (ask >= n - 1 - all.phi.cols()) {
        result.status = {StatusCode::kNoConvergence,
                         fmt::format("no gap between the eigenvalues above {:.6g} rad^2/s^2 to put a shift in",
                                     here->sigma())};
        return result;
      }
      grow *= 2;
      continue;
    }
    grow = shrink = 1;
    wide = false;
    const std::size_t i = *gap;
    const double shift = (std::max(points[i], last && cut ? lambda_cut : points[i]) + points[i + 1]) / 2.0;
    ++result.factorizations;
    cpu_s = thread_cpu_s();
    if (!next->factorize_indefinite(shift).ok()) {
      result.status = next->status();
      return result;
    }
    result.factor_cpu_s += thread_cpu_s() - cpu_s;
    // The Sturm counts at both shifts: exactly this many eigenvalues
    // between them.
    const Eigen::Index expected = next->eigenvalues_below() - here->eigenvalues_below();
    const auto in_slice = [&] {
      return static_cast<Eigen::Index>(
          std::count_if(slice.lambda.begin(), slice.lambda.end(), [&](double l) { return l < shift; }));
    };
    // Missed ones (a multiple eigenvalue, to rounding, can hide from one
    // Krylov space): searched again, deflated against what was found.
    for (int retry = 0; retry < 3 && in_slice() < expected; ++retry) {
      const Eigen::Index missing = expected - in_slice();
      DenseMatrix known(n, all.phi.cols() + near.phi.cols());
      known << all.phi, near.phi;
      Pairs more = solver->nearest(M, *here, std::min(n - known.cols() - 1, 2 * missing + 4), known,
                                   options.lanczos_max_restarts);
      result.iterations += more.iterations;
      if (!more.status.ok()) break;
      merge(near, more);
      merge(slice, above(more, here->sigma()));
    }
    if (in_slice() != expected) {
      result.status = {StatusCode::kNoConvergence,
                       fmt::format("between the shifts {:.6g} and {:.6g} rad^2/s^2 the Sturm count gives {} "
                                   "eigenvalues, Lanczos found {}",
                                   here->sigma(), shift, expected, in_slice())};
      return result;
    }
    slice.lambda.resize(static_cast<std::size_t>(expected));
    slice.phi = slice.phi.leftCols(expected).eval();
    merge(all, slice);
    if (last) break;
    std::unique_ptr<ShiftInvertFactor> spare =
        owned ? std::move(owned) : std::make_unique<ShiftInvertFactor>(K, M, options.indefinite);
    owned = std::move(next);
    here = owned.get();
    next = std::move(spare);
  }

  auto keep = std::min(modes, static_cast<Eigen::Index>(all.lambda.size()));
  if (cut)
    keep = std::max(keep, static_cast<Eigen::Index>(std::count_if(all.lambda.begin(), all.lambda.end(),
                                                                  [&](double l) { return l <= lambda_cut; })));
  result.shapes = all.phi.leftCols(keep);
  for (Eigen::Index k = 0; k < keep; ++k) {
    // A rigid-body mode comes out as a tiny negative lambda: frequency 0.
    const double lambda = all.lambda[static_cast<std::size_t>(k)];
    result.frequencies_hz.push_back(std::sqrt(std::max(lambda, 0.0)) / (2.0 * std::numbers::pi));
    // The sign: the largest entry positive (the same shapes on every run).
    auto phi = result.shapes.col(k);
    Eigen::Index at = 0;
    phi.cwiseAbs().maxCoeff(&at);
    if (phi[at] < 0.0) phi = -phi;
  }
  return result;
}

Eigen::Index count_modes_below(const SparseMatrix& K, const SparseMatrix& M, double frequency_hz, Status* status,
                               IndefiniteFactorizer indefinite) {
  ShiftInvertFactor factor(K, M, indefinite);
  const Status& s = factor.factorize_indefinite(eigenvalue_of(frequency_hz));
  if (status) *status = s;
  return s.ok() ? factor.eigenvalues_below() : -1;
}

}  // namespace railvsi

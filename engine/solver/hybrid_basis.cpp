#include "solver/hybrid_basis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <optional>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "core/input_error.hpp"
#include "core/thread_cpu_time.hpp"
#include "solver/dense_products.hpp"
#include "solver/interface_last_factor.hpp"
#include "solver/lanczos_slices.hpp"
#include "solver/modal_analysis.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {
namespace {

// Below this many, the interior's modes come in slices of 50, else 100.
constexpr Eigen::Index kNarrowSliceInteriorDofs = 10000;

enum class Part : char { kTrack, kInterface, kInterior };

// Each DOF's part: track (the structure's track DOFs), interface (a bridge
// DOF a track DOF couples to in K, M or C) or interior.
std::vector<Part> parts(const StructureModel& s) {
  const int n = s.num_dofs();
  std::vector<Part> part(static_cast<std::size_t>(n), Part::kInterior);
  for (int d = 0; d < n; ++d)
    if (s.info().is_track_dof(d)) part[static_cast<std::size_t>(d)] = Part::kTrack;
  for (const SparseMatrix* A : {&s.K(), &s.M(), &s.C()})
    for (int j = 0; j < A->outerSize(); ++j) {
      if (part[static_cast<std::size_t>(j)] != Part::kTrack) continue;
      for (SparseMatrix::InnerIterator it(*A, j); it; ++it)
        if (part[static_cast<std::size_t>(it.row())] != Part::kTrack && it.value() != 0.0)
          part[static_cast<std::size_t>(it.row())] = Part::kInterface;
    }
  return part;
}

std::string unavailable(const StructureModel& s, const std::vector<Part>& part) {
  if (std::none_of(part.begin(), part.end(), [](Part p) { return p == Part::kTrack; }))
    return "the hybrid structure keeps the track in finite elements, and this structure has no track DOFs (a deck "
           "without track, or an import map without track_nodes/track_dofs): use \"modal\" or \"fe\"";
  for (int d : s.rail_dofs())
    if (part[static_cast<std::size_t>(d)] != Part::kTrack)
      return fmt::format("the hybrid structure needs the rails in the track, and rail DOF {} is a bridge DOF: use "
                         "\"modal\" or \"fe\"",
                         d);
  return "";
}

// The blocks of one structure matrix that the reduction reads.
struct Blocks {
  SparseMatrix II, IG;  // interior x interior, interior x interface
  DenseMatrix GG;       // interface x interface
};

Blocks split(const SparseMatrix& A, const std::vector<Part>& part, const std::vector<int>& local, int n_interior,
             int n_interface) {
  std::vector<Triplet> ii, ig;
  Blocks b;
  b.GG = DenseMatrix::Zero(n_interface, n_interface);
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const auto i = static_cast<std::size_t>(it.row());
      const Part pi = part[i], pj = part[static_cast<std::size_t>(j)];
      const int li = local[i], lj = local[static_cast<std::size_t>(j)];
      if (pi == Part::kInterior && pj == Part::kInterior) ii.emplace_back(li, lj, it.value());
      else if (pi == Part::kInterior && pj == Part::kInterface) ig.emplace_back(li, lj, it.value());
      else if (pi == Part::kInterface && pj == Part::kInterface) b.GG(li, lj) += it.value();
    }
  b.II.resize(n_interior, n_interior);
  b.II.setFromTriplets(ii.begin(), ii.end());
  b.IG.resize(n_interior, n_interface);
  b.IG.setFromTriplets(ig.begin(), ig.end());
  return b;
}

// The bridge's interior and interface as one matrix (interior first, then
// the interface): the bridge without its track.
SparseMatrix bridge_block(const SparseMatrix& A, const std::vector<Part>& part, const std::vector<int>& local,
                          int n_interior, int n_interface) {
  std::vector<Triplet> t;
  const auto at = [&](std::size_t d) { return part[d] == Part::kInterior ? local[d] : n_interior + local[d]; };
  for (int j = 0; j < A.outerSize(); ++j) {
    const auto uj = static_cast<std::size_t>(j);
    if (part[uj] == Part::kTrack) continue;
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const auto ui = static_cast<std::size_t>(it.row());
      if (part[ui] != Part::kTrack) t.emplace_back(at(ui), at(uj), it.value());
    }
  }
  SparseMatrix B(n_interior + n_interface, n_interior + n_interface);
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

// Rayleigh-Ritz of the interior (K_II, M_II) on the columns of Q: an
// M_II-orthonormal basis of their span whose K_II block is diagonal,
// ascending, and its frequencies (Hz). Directions of Q that are (nearly)
// dependent, relative 1e-10 in Q' M_II Q, are dropped: with every free mode
// kept, Q has more columns than the interior has DOFs.
std::pair<DenseMatrix, std::vector<double>> interior_ritz(const SparseMatrix& K, const SparseMatrix& M,
                                                          const DenseMatrix& Q) {
  DenseMatrix SM;
  multiply_transposed(Q, sparse_times_dense(M, Q), SM);
  SM = (0.5 * (SM + SM.transpose())).eval();
  Eigen::SelfAdjointEigenSolver<DenseMatrix> em(SM);
  const Eigen::VectorXd& d = em.eigenvalues();
  const double largest = d.size() ? d.maxCoeff() : 0.0;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < d.size(); ++k)
    if (d(k) > 1e-10 * largest) keep.push_back(k);
  DenseMatrix U(SM.rows(), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k)
    U.col(static_cast<Eigen::Index>(k)) = em.eigenvectors().col(keep[k]) / std::sqrt(d(keep[k]));
  const DenseMatrix B = Q * U;
  DenseMatrix SK;
  multiply_transposed(B, sparse_times_dense(K, B), SK);
  SK = (0.5 * (SK + SK.transpose())).eval();
  Eigen::SelfAdjointEigenSolver<DenseMatrix> ek(SK);
  std::vector<double> f;
  for (Eigen::Index k = 0; k < ek.eigenvalues().size(); ++k)
    f.push_back(std::sqrt(std::max(ek.eigenvalues()(k), 0.0)) / (2.0 * std::numbers::pi));
  return {B * ek.eigenvectors(), std::move(f)};
}

// The modes of (K, M), mass-normalised: the interior's with the interface
// held, or the bridge's own (K_BB, M_BB, its interface free).
// `factor`: K's L L' factor (the constraint modes'), the first shift (0),
// or null (the solver's own at -1).
ModalResult interior_modes(const SparseMatrix& K, const SparseMatrix& M, const HybridBasisOptions& o,
                           const ShiftInvertFactor* factor, HybridBasisSummary& summary) {
  const Eigen::Index n = K.rows();
  ModalResult r;
  if (n == 0) return r;
  // Dense: every mode, or a model too small for the iterative solver.
  const bool dense = o.all_modes || n <= 400;
  if (dense) {
    if (n > 6000)
      throw InputError("/analysis/structure",
                       fmt::format("every interior mode of {} DOFs is too many for a dense eigensolver: give "
                                   "cutoff_hz or modes",
                                   n));
    const DenseMatrix Kd(K), Md(M);
    Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> es(Kd, Md);
    if (es.info() != Eigen::Success)
      throw InputError("/structure", "the bridge interior's modes could not be computed (dense eigensolver)");
    Eigen::Index keep = n;
    if (!o.all_modes) {
      keep = 0;
      const double wmax = 2.0 * std::numbers::pi * o.max_frequency_hz;
      if (o.modes > 0) keep = std::min<Eigen::Index>(o.modes, n);
      else
        while (keep < n && es.eigenvalues()[keep] <= wmax * wmax) ++keep;
    }
    r.shapes = es.eigenvectors().leftCols(keep);  // M-normalised by Eigen
    for (Eigen::Index k = 0; k < keep; ++k)
      r.frequencies_hz.push_back(std::sqrt(std::max(es.eigenvalues()[k], 0.0)) / (2.0 * std::numbers::pi));
    return r;
  }
  ModalOptions mo;
  // Asked for its modes up to a cut-off, the interior counts them first (one
  // L D L' factor at the cut-off) and asks exactly that many of the first
  // shift, certified when all lie below the cut-off (ModalOptions::
  // modes_below_cutoff): a slice of the usual 100 modes reaches past the
  // cut-off, into a band it converges slowly in, and needs a factor past it
  // to certify the count (at seed scale the same MUMPS factor; 78 modes to
  // 221 Hz asked as 78 rather than 100, docs/performance.md).
  double count_cpu_s = thread_cpu_s();
  const Eigen::Index counted = o.modes == 0 ? count_modes_below(K, M, o.max_frequency_hz) : Eigen::Index{-1};
  count_cpu_s = thread_cpu_s() - count_cpu_s;
  if (o.modes > 0) {
    mo.modes = std::min<int>(o.modes, static_cast<int>(n) - 1);
  } else {
    // Every mode up to the cut-off, the count certified by a Sturm count
    // (the one made here, or the slices' own when it failed).
    mo.modes = 0;
    mo.max_frequency_hz = o.max_frequency_hz;
    mo.modes_below_cutoff = static_cast<int>(counted);
  }
  // The bridge without its track has no band of nearly equal modes: one
  // slice takes the usual 60-100 modes with one factor (measured on the
  // 20,000-DOF deck to 221 Hz, 78 modes: 2 factors and 3.1 s against 5 and
  // 5.2 s in slices of 30). A small interior's factor is cheap and its
  // Lanczos basis's orthogonalization is not: slices of 50 (6,042-DOF deck
  // to 221 Hz, 84 modes: 0.96 s against 4.0 s in slices of 100;
  // tests/bench/hybrid_bench --cost, 2026-11-27).
  mo.slice_modes = n < kNarrowSliceInteriorDofs ? 50 : 100;
  // Block Lanczos: the factor (10^8 nonzeros at seed scale) read once per
  // 16 vectors (interior modes 76.1 -> 56.3 s at seed scale, docs/performance.md).
  mo.lanczos_block = 16;
  if (factor) mo.shift_rad2_per_s2 = factor->sigma();
  r = modal_analysis(K, M, mo, factor);
  if (counted >= 0) {
    ++r.factorizations;
    r.factor_cpu_s += count_cpu_s;
  }
  summary.interior_max_residual = r.max_residual;
  summary.interior_block_residual = r.block_residual;
  summary.interior_single_vector_fallback = r.block_fallback;
  if (!r.status.ok())
    throw InputError("/structure", "the bridge interior's modes could not be computed: " + r.status.message());
  return r;
}

// (a0, a1) when the bridge's damping couples its interior as Rayleigh
// damping, C_II = a0 M_II + a1 K_II and C_IG = a0 M_IG + a1 K_IG, to
// `tolerance` of C's largest entry there; nullopt otherwise. Fitted on the
// interior's diagonal (columns scaled), then checked on every entry.
std::optional<std::pair<double, double>> interior_rayleigh(const Blocks& C, const Blocks& M, const Blocks& K,
                                                           double tolerance) {
  if (C.II.rows() == 0) return std::nullopt;  // no interior: nothing to save
  const Eigen::VectorXd c = C.II.diagonal(), m = M.II.diagonal(), k = K.II.diagonal();
  const double m_scale = m.cwiseAbs().maxCoeff(), k_scale = k.cwiseAbs().maxCoeff();
  if (!(m_scale > 0.0) || !(k_scale > 0.0)) return std::nullopt;
  Eigen::MatrixX2d A(c.size(), 2);
  A.col(0) = m / m_scale;
  A.col(1) = k / k_scale;
  const Eigen::Vector2d x = A.colPivHouseholderQr().solve(c);
  const double a0 = x(0) / m_scale, a1 = x(1) / k_scale;
  if (!std::isfinite(a0) || !std::isfinite(a1)) return std::nullopt;
  const auto off = [&](const SparseMatrix& Cb, const SparseMatrix& Mb, const SparseMatrix& Kb, double& largest) {
    const SparseMatrix r = Cb - a0 * Mb - a1 * Kb;
    largest = std::max(largest, Cb.coeffs().size() ? Cb.coeffs().cwiseAbs().maxCoeff() : 0.0);
    return r.coeffs().size() ? r.coeffs().cwiseAbs().maxCoeff() : 0.0;
  };
  double largest = 0.0;
  const double r_ii = off(C.II, M.II, K.II, largest), r_ig = off(C.IG, M.IG, K.IG, largest);
  if (!(largest > 0.0) || !(std::max(r_ii, r_ig) <= tolerance * largest)) return std::nullopt;
  return std::make_pair(a0, a1);
}

void add_dense(std::vector<Triplet>& t, const DenseMatrix& B, int row0, int col0) {
  for (Eigen::Index j = 0; j < B.cols(); ++j)
    for (Eigen::Index i = 0; i < B.rows(); ++i)
      if (B(i, j) != 0.0) t.emplace_back(row0 + static_cast<int>(i), col0 + static_cast<int>(j), B(i, j));
}

}  // namespace

HybridPartition hybrid_partition(const StructureModel& structure) {
  const std::vector<Part> part = parts(structure);
  HybridPartition p;
  p.unavailable = unavailable(structure, part);
  for (Part x : part) {
    if (x == Part::kTrack) ++p.track_dofs;
    else if (x == Part::kInterface) ++p.interface_dofs;
    else ++p.interior_dofs;
  }
  return p;
}

HybridBasis::HybridBasis(std::shared_ptr<const StructureModel> structure, const HybridBasisOptions& options)
    : structure_(std::move(structure)) {
  const StructureModel& s = *structure_;
  const int n = s.num_dofs();
  if (!options.all_modes && options.modes <= 0 && !(options.max_frequency_hz > 0.0))
    throw InputError("/analysis/cutoff_hz", "the hybrid structure needs a cut-off frequency > 0 or a mode count");
  if (options.column_block < 1) throw InputError("/analysis/structure", "the hybrid reduction's column block must be >= 1");
  const int block = options.column_block;
  const std::vector<Part> part = parts(s);
  if (const std::string why = unavailable(s, part); !why.empty()) throw InputError("/analysis/structure", why);
  std::vector<int> local(static_cast<std::size_t>(n));
  int n_interior = 0;
  for (int d = 0; d < n; ++d) {
    const auto u = static_cast<std::size_t>(d);
    local[u] = part[u] == Part::kTrack       ? n_track_++
               : part[u] == Part::kInterface ? n_interface_++
                                             : n_interior++;
  }
  const Blocks K = split(s.K(), part, local, n_interior, n_interface_);
  const Blocks M = split(s.M(), part, local, n_interior, n_interface_);
  const Blocks C = split(s.C(), part, local, n_interior, n_interface_);

  // Psi = -K_II^-1 K_IG. With free-interface modes, from one factor of the
  // whole bridge with the interface ordered last (interface_last_factor.hpp:
  // backward solves only), which is also the modes' shift-invert operator
  // at shift 0. Else, or when the bridge without its track is not positive
  // definite, from one factor of K_II (positive definite: the interface
  // held supports the interior), solved a block of columns at a time: the
  // dense K_IG and CHOLMOD's workspace stay a block wide.
  double cpu_s = thread_cpu_s();
  DenseMatrix Psi(n_interior, n_interface_);
  bridge_modes_ = options.bridge_modes;
  const bool free_modes = bridge_modes_ == BridgeModes::kFreeInterface && n_interior > 0;
  SparseMatrix K_BB, M_BB;  // the bridge without its track (free-interface modes)
  if (free_modes) {
    K_BB = bridge_block(s.K(), part, local, n_interior, n_interface_);
    M_BB = bridge_block(s.M(), part, local, n_interior, n_interface_);
  }
  std::unique_ptr<ShiftInvertFactor> bridge_factor;  // K_BB's, interface last
  if (free_modes && n_interface_ > 0 && options.interface_last_factor) {
    Status ordered;
    std::vector<int> order = interface_last_ordering(K.II, n_interface_, ordered);
    if (ordered.ok()) {
      bridge_factor = std::make_unique<ShiftInvertFactor>(K_BB, M_BB);
      bridge_factor->order_as(std::move(order));
      if (!bridge_factor->factorize(0.0).ok() || !constraint_modes(*bridge_factor, n_interior, block, Psi))
        bridge_factor.reset();
    }
  }
  // K_II's factor: the fixed-interface modes' first shift (0: below the
  // spectrum, the interface held).
  std::unique_ptr<ShiftInvertFactor> factor;
  if (!bridge_factor && n_interior > 0 && n_interface_ > 0) {
    factor = std::make_unique<ShiftInvertFactor>(K.II, M.II);
    if (!factor->factorize(0.0).ok())
      throw InputError("/structure", "the bridge with its track-bearing DOFs held is not supported: " +
                                         factor->status().message());
    DenseMatrix rhs, x;
    for (int c0 = 0; c0 < n_interface_; c0 += block) {
      const int w = std::min(block, n_interface_ - c0);
      rhs = DenseMatrix(K.IG.middleCols(c0, w));
      if (!factor->solve(rhs, x))
        throw InputError("/structure", "CHOLMOD failed to solve for the bridge's constraint modes");
      Psi.middleCols(c0, w) = -x;
    }
  }
  summary_.constraint_modes_cpu_s = thread_cpu_s() - cpu_s;
  summary_.shared_bridge_factor = bridge_factor != nullptr;
  cpu_s = thread_cpu_s();
  ModalResult modes;
  if (bridge_modes_ == BridgeModes::kFixedInterface) {
    modes = interior_modes(K.II, M.II, options, factor.get(), summary_);
    factor.reset();
    frequencies_hz_ = modes.frequencies_hz;
  } else if (n_interior > 0) {
    // The bridge's own modes (its interface free), each less its static
    // interface part, then orthonormalised on the interior.
    factor.reset();
    ModalResult free = interior_modes(K_BB, M_BB, options, bridge_factor.get(), summary_);
    bridge_factor.reset();
    bridge_frequencies_hz_ = free.frequencies_hz;
    const DenseMatrix Q = free.shapes.topRows(n_interior) - Psi * free.shapes.bottomRows(n_interface_);
    auto [basis, ritz_hz] = interior_ritz(K.II, M.II, Q);
    modes.shapes = std::move(basis);
    modes.factorizations = free.factorizations;
    modes.factor_cpu_s = free.factor_cpu_s;
    frequencies_hz_ = std::move(ritz_hz);
  }
  summary_.interior_modes_cpu_s = thread_cpu_s() - cpu_s;
  summary_.factorizations = modes.factorizations;
  summary_.interior_factor_cpu_s = modes.factor_cpu_s;
  const DenseMatrix& Phi = modes.shapes;
  const int m = num_modes();
  const std::vector<double>& chosen = bridge_frequencies_hz_.empty() ? frequencies_hz_ : bridge_frequencies_hz_;
  cutoff_hz_ = options.modes > 0 || options.all_modes ? (chosen.empty() ? 0.0 : chosen.back())
                                                       : options.max_frequency_hz;

  // T' A T block by block; the track's rows and columns as they are. With
  // W = A_IG + A_II Psi, the interface block is A_GG + A_IG' Psi + Psi' W
  // and its coupling to the modes W' Phi. For K, W = K_IG + K_II Psi = 0
  // (Psi's definition): K_GG + K_IG' Psi, uncoupled from the modes.
  const int g0 = n_track_, q0 = n_track_ + n_interface_;
  // The bridge's blocks of T' A T: interface x interface, interface x
  // modes, modes x modes.
  struct Reduced {
    DenseMatrix GG, Gq, qq;
  };
  const auto reduce_bridge = [&](const Blocks& b, bool stiffness) {
    // With X = A_IG' Psi (sparse times dense): A_GG + X + X' + Psi' A_II Psi,
    // whose last term's symmetry halves the largest product: each block of
    // its columns only from the diagonal down (the lower triangle, mirrored
    // after). For K, Psi' K_II Psi = -X': K_GG + X.
    Reduced r;
    const DenseMatrix X = b.IG.transpose() * Psi;
    r.GG = b.GG + X;
    r.Gq = DenseMatrix::Zero(n_interface_, m);
    DenseMatrix Z, WPhi;
    SparseProductWorkspace work;
    if (!stiffness) {
      DenseMatrix S = DenseMatrix::Zero(n_interface_, n_interface_);
      for (int c0 = 0; c0 < n_interface_; c0 += block) {
        const int w = std::min(block, n_interface_ - c0);
        sparse_times_dense(b.II, Psi.middleCols(c0, w), Z, work);
        multiply_blocks(true, Psi.rightCols(n_interface_ - c0), Z, S.block(c0, c0, n_interface_ - c0, w));
        // W = Z + A_IG's columns, added in place (no dense copy of A_IG's
        // block: the same sums).
        for (int k = 0; k < w; ++k)
          for (SparseMatrix::InnerIterator it(b.IG, c0 + k); it; ++it) Z(it.row(), k) += it.value();
        multiply_transposed(Z, Phi, WPhi);
        r.Gq.middleRows(c0, w) = WPhi;
      }
      S.triangularView<Eigen::StrictlyUpper>() = S.transpose();
      r.GG += X.transpose() + S;
    }
    r.GG = (0.5 * (r.GG + r.GG.transpose())).eval();
    multiply_transposed(Phi, sparse_times_dense(b.II, Phi), r.qq);
    r.qq = (0.5 * (r.qq + r.qq.transpose())).eval();
    return r;
  };
  // T' A T: the track's rows and columns as they are, the bridge's blocks.
  const auto assemble = [&](const SparseMatrix& A, const Reduced& r) {
    std::vector<Triplet> t;
    for (int j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
        const auto i = static_cast<std::size_t>(it.row());
        const Part pi = part[i], pj = part[static_cast<std::size_t>(j)];
        if (pi == Part::kInterior || pj == Part::kInterior) continue;
        if (pi == Part::kInterface && pj == Part::kInterface) continue;  // in GG
        const int ri = pi == Part::kTrack ? local[i] : g0 + local[i];
        const int rj = pj == Part::kTrack ? local[static_cast<std::size_t>(j)] : g0 + local[static_cast<std::size_t>(j)];
        t.emplace_back(ri, rj, it.value());
      }
    add_dense(t, r.GG, g0, g0);
    add_dense(t, r.Gq, g0, q0);
    add_dense(t, r.Gq.transpose(), q0, g0);
    add_dense(t, r.qq, q0, q0);
    SparseMatrix R(size(), size());
    R.setFromTriplets(t.begin(), t.end());
    R.makeCompressed();
    return R;
  };
  index_.assign(static_cast<std::size_t>(n), -1);
  for (int d = 0; d < n; ++d) {
    const auto u = static_cast<std::size_t>(d);
    if (part[u] == Part::kTrack) index_[u] = local[u];
    else if (part[u] == Part::kInterface) index_[u] = g0 + local[u];
  }
  std::vector<RailLine> rails = s.rails();
  for (RailLine& line : rails)
    for (auto& e : line.element_dofs)
      for (int& d : e) d = index(d);
  StructureInfo info;
  info.source = s.info().source + " (hybrid)";
  info.bridge_start_m = s.info().bridge_start_m;
  info.bridge_end_m = s.info().bridge_end_m;
  info.first_frequency_hz = s.info().first_frequency_hz;
  info.track_dofs = n_track_;
  info.deck_dofs = size() - n_track_;
  for (int d = 0; d < n_track_; ++d) info.track_dof_list.push_back(d);
  cpu_s = thread_cpu_s();
  const Reduced rK = reduce_bridge(K, true), rM = reduce_bridge(M, false);
  Reduced rC;
  const auto rayleigh = options.rayleigh_shortcut ? interior_rayleigh(C, M, K, kRayleighFitTolerance) : std::nullopt;
  if (rayleigh) {
    // C = a0 M + a1 K on the bridge's interior: its blocks follow from M's
    // and K's (W_K = 0, so C couples the modes through M only), which
    // saves the largest product, Psi' C_II Psi.
    const auto [a0, a1] = *rayleigh;
    rC.GG = C.GG + a0 * (rM.GG - M.GG) + a1 * (rK.GG - K.GG);
    rC.GG = (0.5 * (rC.GG + rC.GG.transpose())).eval();
    rC.Gq = a0 * rM.Gq;
    rC.qq = a0 * rM.qq + a1 * rK.qq;
  } else {
    rC = reduce_bridge(C, false);
  }
  summary_.rayleigh_damping = rayleigh.has_value();
  reduced_ = std::make_shared<const StructureModel>(assemble(s.K(), rK), assemble(s.M(), rM), assemble(s.C(), rC),
                                                    std::move(rails), std::vector<OutputPoint>{}, std::move(info));

  summary_.reduction_cpu_s = thread_cpu_s() - cpu_s;

  // Rows of the interior DOFs that runs read.
  row_of_.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> kept;
  for (const OutputPoint& o : s.outputs())
    if (o.dof >= 0 && part[static_cast<std::size_t>(o.dof)] == Part::kInterior) kept.push_back(o.dof);
  if (s.info().deck_beam)
    for (int d = 0; d < n; ++d)
      if (part[static_cast<std::size_t>(d)] == Part::kInterior) kept.push_back(d);
  std::sort(kept.begin(), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  rows_.resize(n_interface_ + m, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const int li = local[static_cast<std::size_t>(kept[k])];
    row_of_[static_cast<std::size_t>(kept[k])] = static_cast<int>(k);
    auto col = rows_.col(static_cast<Eigen::Index>(k));
    col.head(n_interface_) = Psi.row(li).transpose();
    col.tail(m) = Phi.row(li).transpose();
  }
}

const double* HybridBasis::row(int dof) const {
  if (dof < 0) return nullptr;
  const int r = row_of_[static_cast<std::size_t>(dof)];
  return r < 0 ? nullptr : rows_.col(r).data();
}

std::size_t HybridBasis::memory_bytes() const {
  const StructureModel& r = *reduced_;
  const auto nnz = static_cast<std::size_t>(r.K().nonZeros() + r.M().nonZeros() + r.C().nonZeros());
  return sizeof(*this) + nnz * (sizeof(double) + sizeof(int)) +
         static_cast<std::size_t>(rows_.size()) * sizeof(double) + (index_.size() + row_of_.size()) * sizeof(int);
}

std::string HybridBasis::describe() const {
  return fmt::format("hybrid: track in FE ({} DOFs), bridge in {} {}modes up to {:.4g} Hz with {} interface DOFs",
                     n_track_, num_modes(), modes_label(), cutoff_hz_, n_interface_);
}

}  // namespace railvsi

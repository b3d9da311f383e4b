#include "solver/mumps_ldlt.hpp"

#include <algorithm>
#include <mutex>
#include <vector>

#include <dmumps_c.h>
#include <fmt/format.h>

namespace railvsi {
namespace {

constexpr MUMPS_INT kUseCommWorld = -987654;  // the sequential library's only communicator
constexpr MUMPS_INT kInit = -1, kEnd = -2, kFactorize = 2, kAnalyseFactorize = 4, kSolve = 3;
constexpr MUMPS_INT kSymmetricIndefinite = 2;

// The sequential MUMPS keeps state of its own outside an instance (its load
// balancing's module variables): two instances called at once from two
// threads abort the process ("PB allocation in DMUMPS_LOAD_INIT", measured
// with Debian's 5.5.1). So every call into it holds this lock; the library,
// not railvsi, is what it guards.
void call_mumps(DMUMPS_STRUC_C& id) {
  static std::mutex library;
  const std::lock_guard<std::mutex> hold(library);
  dmumps_c(&id);
}

// MUMPS's ICNTL(k) and INFOG(k) are 1-based in its documentation.
MUMPS_INT& icntl(DMUMPS_STRUC_C& id, int k) { return id.icntl[k - 1]; }
MUMPS_INT infog(const DMUMPS_STRUC_C& id, int k) { return id.infog[k - 1]; }

}  // namespace

// One MUMPS instance and the matrix it was given (MUMPS keeps pointers to
// the triplets between the analysis and the factorization).
struct MumpsLdlt::Instance {
  DMUMPS_STRUC_C id{};
  bool started = false;
  bool analysed = false;  // rows, cols: the pattern of the last analysis
  bool factorized = false;
  std::vector<MUMPS_INT> rows, cols;  // 1-based
  std::vector<double> values;
  mutable std::vector<double> rhs;  // the solves' workspace: MUMPS overwrites the right-hand side

  Instance() {
    id.job = kInit;
    id.par = 1;
    id.sym = kSymmetricIndefinite;
    id.comm_fortran = kUseCommWorld;
    call_mumps(id);
    started = infog(id, 1) >= 0;
    // Silent: failures come back as statuses.
    icntl(id, 1) = -1;
    icntl(id, 2) = -1;
    icntl(id, 3) = -1;
    icntl(id, 4) = 0;
    // Null pivots detected (INFOG(28)): a singular matrix is an error, not
    // a factor with an arbitrary pivot.
    icntl(id, 24) = 1;
    // PORD's ordering: the automatic choice of the sequential library
    // (without METIS) is SCOTCH's, whose factor of the seed-scale bridge
    // interior at its 221 Hz cut-off has 1.37e8 entries and 1.1e11 flops
    // (7.6-8.6 s); PORD's 1.22e8 and 9.2e10 (6.7 s; 50,000-DOF deck 0.64 ->
    // 0.50 s). The inertia, the Sturm count, does not depend on it.
    icntl(id, 7) = 4;
  }
  ~Instance() {
    if (!started) return;
    id.job = kEnd;
    call_mumps(id);
  }
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
};

MumpsLdlt::MumpsLdlt() : instance_(std::make_unique<Instance>()) {}
MumpsLdlt::~MumpsLdlt() = default;

Status MumpsLdlt::factorize(const SparseMatrix& A) {
  Instance& s = *instance_;
  s.factorized = false;
  if (!s.started) return {StatusCode::kDiverged, "MUMPS could not start an instance"};
  std::vector<MUMPS_INT> rows, cols;
  s.values.clear();
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() >= j) {
        rows.push_back(static_cast<MUMPS_INT>(it.row() + 1));
        cols.push_back(static_cast<MUMPS_INT>(j + 1));
        s.values.push_back(it.value());
      }
  // The shifts of one analysis share a pattern: its ordering is kept.
  const bool same_pattern = s.analysed && rows == s.rows && cols == s.cols;
  s.analysed = same_pattern;
  s.rows = std::move(rows);
  s.cols = std::move(cols);
  DMUMPS_STRUC_C& id = s.id;
  id.n = static_cast<MUMPS_INT>(A.rows());
  id.nnz = static_cast<MUMPS_INT8>(s.values.size());
  id.irn = s.rows.data();
  id.jcn = s.cols.data();
  id.a = s.values.data();
  // Working space over the analysis's estimate, in percent; raised when the
  // factorization runs out of it (INFOG(1) = -8, -9: numerical pivoting
  // delayed more pivots than estimated).
  icntl(id, 14) = 30;
  for (int attempt = 0; attempt < 3; ++attempt) {
    id.job = same_pattern && attempt == 0 ? kFactorize : kAnalyseFactorize;
    call_mumps(id);
    const MUMPS_INT error = infog(id, 1);
    if (error >= 0) {
      s.analysed = true;
      if (infog(id, 28) > 0)
        return {StatusCode::kDiverged, fmt::format("MUMPS: the {} x {} matrix is singular ({} null pivots)", id.n,
                                                   id.n, infog(id, 28))};
      s.factorized = true;
      return Status::Ok();
    }
    if (error == -10)
      return {StatusCode::kDiverged, fmt::format("MUMPS: the {} x {} matrix is singular to its pivot threshold", id.n, id.n)};
    if (error != -8 && error != -9)
      return {StatusCode::kDiverged,
              fmt::format("MUMPS could not factorize a {} x {} matrix (INFOG(1) = {}, INFOG(2) = {})", id.n, id.n,
                          error, infog(id, 2))};
    icntl(id, 14) *= 3;
  }
  return {StatusCode::kDiverged, fmt::format("MUMPS ran out of working space factorizing a {} x {} matrix", id.n, id.n)};
}

bool MumpsLdlt::factorized() const { return instance_->factorized; }

Eigen::Index MumpsLdlt::negative_pivots() const { return factorized() ? infog(instance_->id, 12) : 0; }

bool MumpsLdlt::solve(const DenseMatrix& B, DenseMatrix& X) const {
  if (!factorized() || B.rows() != instance_->id.n) return false;
  instance_->rhs.assign(B.data(), B.data() + B.size());
  if (!solve_in_place(static_cast<int>(B.cols()))) return false;
  X = Eigen::Map<const DenseMatrix>(instance_->rhs.data(), B.rows(), B.cols());
  return true;
}

bool MumpsLdlt::solve(const double* x, double* y) const {
  if (!factorized()) return false;
  const Eigen::Index n = instance_->id.n;
  instance_->rhs.assign(x, x + n);
  if (!solve_in_place(1)) return false;
  std::copy_n(instance_->rhs.data(), n, y);
  return true;
}

bool MumpsLdlt::solve_in_place(int columns) const {
  DMUMPS_STRUC_C& id = instance_->id;
  id.job = kSolve;
  id.rhs = instance_->rhs.data();
  id.nrhs = static_cast<MUMPS_INT>(columns);
  id.lrhs = id.n;
  call_mumps(id);
  return infog(id, 1) >= 0;
}

}  // namespace railvsi

#pragma once
// A CHOLMOD factor of K - sigma M for the mode solvers: y = (K - sigma M)^-1 x
// for one vector (Lanczos) or a block of them (subspace iteration; one solve
// of many columns runs on BLAS-3 kernels). Below the spectrum it is L L'
// (supernodal, BLAS-3); inside it L D L', whose inertia counts the
// eigenvalues below the shift (spectrum slicing, lanczos_slices.hpp): by
// MUMPS, or CHOLMOD's simplicial factor (IndefiniteFactorizer).
#include <memory>
#include <optional>
#include <vector>

#include "core/status.hpp"
#include "core/types.hpp"
#include "solver/cholmod_handles.hpp"
#include "solver/modal_types.hpp"
#include "solver/mumps_ldlt.hpp"

namespace railvsi {

class ShiftInvertFactor {
 public:
  // Keeps references to K and M: both must outlive the factor.
  ShiftInvertFactor(const SparseMatrix& K, const SparseMatrix& M,
                    IndefiniteFactorizer indefinite = IndefiniteFactorizer::kMumps)
      : K_(K), M_(M), indefinite_factorizer_(indefinite) {}
  ~ShiftInvertFactor();
  ShiftInvertFactor(const ShiftInvertFactor&) = delete;
  ShiftInvertFactor& operator=(const ShiftInvertFactor&) = delete;

  // Factorizes K - sigma M as L L' (a repeated sigma keeps the factor). Not
  // positive definite (a shift above an eigenvalue, or a mechanism) is a
  // Status: an L D L' factor would accept it, and the "lowest" modes found
  // would silently skip those below the shift.
  const Status& factorize(double sigma);
  // Factorizes K - sigma M as L D L' for a shift inside the spectrum: by
  // MUMPS (with pivoting), or by CHOLMOD simplicial without pivoting (its
  // supernodal factor is L L' only). A zero pivot (sigma an eigenvalue to
  // rounding) is a Status.
  const Status& factorize_indefinite(double sigma);
  // The L L' factors that follow use this fill-reducing permutation as it
  // is (row k of L is DOF permutation[k]), without CHOLMOD's postorder,
  // which could move a trailing block (interface_last_factor.hpp) forward.
  // Empty: CHOLMOD's own ordering. Call before factorize().
  void order_as(std::vector<int> permutation) { given_ordering_ = std::move(permutation); }
  const Status& status() const { return status_; }
  // The number of eigenvalues below the shift factorized (Sylvester's law
  // of inertia: the negative entries of D; 0 after factorize()). The Sturm
  // count of spectrum slicing.
  Eigen::Index eigenvalues_below() const { return eigenvalues_below_; }
  double sigma() const { return sigma_.value_or(0.0); }
  Eigen::Index rows() const { return K_.rows(); }

  // The solves share workspaces: one caller at a time (not reentrant).
  // y = (K - sigma M)^-1 x for n values; NaN in y if CHOLMOD fails.
  void solve(const double* x, double* y) const;
  // X = (K - sigma M)^-1 B, all columns in one solve; false if CHOLMOD fails.
  bool solve(const DenseMatrix& B, DenseMatrix& X) const;
  // The CHOLMOD L L' factor (null with MUMPS's L D L', or none), to read L
  // and to solve with its parts (CHOLMOD_L, CHOLMOD_Lt).
  const cholmod_factor* cholmod_l() const { return uses_mumps() ? nullptr : factor_.get(); }
  // X = op^-1 B with CHOLMOD's system `cholmod_system` (CHOLMOD_A, _L,
  // _Lt, ...; B in the factor's order for _L and _Lt); false if it fails.
  bool solve(int cholmod_system, const DenseMatrix& B, DenseMatrix& X) const;

 private:
  using Factor = std::unique_ptr<cholmod_factor, CholmodFactorDeleter>;
  // Factorizes K - sigma M: L L' (supernodal where it pays), or with
  // `indefinite` simplicial L D L'. kStopped: CHOLMOD stopped at a pivot
  // that is not positive (L L') or zero (L D L').
  enum class Outcome { kComplete, kStopped, kFailed };
  Outcome factor_at(double sigma, bool indefinite);
  Status failed(int cholmod_status) const;
  bool uses_mumps() const { return indefinite_ && mumps_ && mumps_->factorized(); }
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  IndefiniteFactorizer indefinite_factorizer_;
  std::unique_ptr<MumpsLdlt> mumps_;  // the L D L' factor when MUMPS made it
  std::unique_ptr<CholmodCommon> common_ = std::make_unique<CholmodCommon>();
  Factor factor_{nullptr, CholmodFactorDeleter{nullptr}};
  // Solve workspaces, reused between the solves of one analysis.
  mutable cholmod_dense* X_ = nullptr;
  mutable cholmod_dense* Y_ = nullptr;
  mutable cholmod_dense* E_ = nullptr;
  std::vector<int> given_ordering_;  // order_as(); empty: CHOLMOD's
  Status status_{StatusCode::kInvalidInput, "not factorized"};
  std::optional<double> sigma_;  // the shift factorized (or failed) last
  bool indefinite_ = false;      // and how
  Eigen::Index eigenvalues_below_ = 0;
};

}  // namespace railvsi

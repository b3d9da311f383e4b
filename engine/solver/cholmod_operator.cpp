#include "solver/cholmod_operator.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "solver/rail_suffix.hpp"

namespace railvsi {
namespace {

class CholmodWorkspace final : public SolveWorkspace {
 public:
  CholmodCommon common;
  // Reused between solves; cholmod_solve2 reallocates only when sizes change.
  cholmod_dense* X = nullptr;
  cholmod_dense* Y = nullptr;
  cholmod_dense* E = nullptr;
  Vector permuted, suffix;  // the split solve's scratch (rail_suffix.hpp)
  ~CholmodWorkspace() override {
    cholmod_free_dense(&X, common.get());
    cholmod_free_dense(&Y, common.get());
    cholmod_free_dense(&E, common.get());
  }
  // Solves for the columns of B; the result is in X.
  bool solve(const cholmod_factor* L, Eigen::Ref<DenseMatrix> B, int system = CHOLMOD_A) {
    cholmod_dense b = cholmod_view(B);
    return cholmod_solve2(system, const_cast<cholmod_factor*>(L), &b, nullptr, &X, nullptr, &Y, &E,
                          common.get()) != 0;
  }
};

// A simplicial LDL' factor accepts an indefinite matrix (negative D); the
// structure must be positive definite, so check D as LL' would have.
size_t first_nonpositive_pivot(const cholmod_factor& L) {
  if (L.is_super || L.is_ll || L.xtype != CHOLMOD_REAL) return L.n;
  const int* p = static_cast<const int*>(L.p);
  const double* x = static_cast<const double*>(L.x);
  for (size_t j = 0; j < L.n; ++j)
    if (!(x[p[j]] > 0.0)) return j;
  return L.n;
}

}  // namespace

namespace {

// The pattern of f's effective matrix lies within the pattern of g's: every
// matrix f uses is used by g (effective_matrix adds a term only when its
// factor is not 0).
bool pattern_within(const EffectiveMatrixFactors& f, const EffectiveMatrixFactors& g) {
  return (f.mass == 0.0 || g.mass != 0.0) && (f.damping == 0.0 || g.damping != 0.0) &&
         (f.stiffness == 0.0 || g.stiffness != 0.0);
}

}  // namespace

CholmodOperator::CholmodOperator(const StructureModel& model, const EffectiveMatrixFactors& factors,
                                 const CholmodOperatorOptions& options, const CholmodOperator* analysis_of)
    : n_(model.num_dofs()), block_columns_(std::max(1, options.flexibility_block_columns)), model_(&model),
      common_(std::make_unique<CholmodCommon>()) {
  factors_ = factors;
  model_dofs_ = n_;
  const auto start = std::chrono::steady_clock::now();
  const SparseMatrix A = effective_matrix(model, factors);
  cholmod_sparse view = cholmod_view_symmetric(A);
  cholmod_common* c = common_->get();
  // Supernodal when the factor is large enough for BLAS-3 to pay (CHOLMOD's
  // own flop-count rule); simplicial solves are several times faster on
  // small banded models such as plane viaducts.
  c->supernodal = CHOLMOD_AUTO;
  // Another operator of the same structure whose matrix pattern contains
  // this one's (K within K_bar) lends its ordering and symbolic analysis: a
  // copy of its factor is refactorized with this matrix.
  // Only for the very model object it was built from: another model with
  // the same size may have another pattern.
  const bool reuse = analysis_of && analysis_of->model_ == &model && pattern_within(factors, analysis_of->factors_);
  factor_ = std::unique_ptr<cholmod_factor, CholmodFactorDeleter>(
      reuse ? cholmod_copy_factor(analysis_of->factor_.get(), c) : cholmod_analyze(&view, c),
      CholmodFactorDeleter{c});
  if (!factor_) throw InputError("/structure", "CHOLMOD could not analyse the structure matrix");
  const std::vector<int>& rails = model.rail_dofs();
  if (!reuse && options.rail_flexibility && options.rails_last_max_fill_growth > 0.0 && !rails.empty()) {
    if (cholmod_factor* last = analyze_with_last(&view, *factor_, c->lnz, rails,
                                                 1.0 + options.rails_last_max_fill_growth, c)) {
      factor_.reset(last);
      suffix_start_ = railvsi::suffix_start(*factor_, rails);
    }
  }
  analysis_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int ok = cholmod_factorize(&view, factor_.get(), c);
  if (!ok || c->status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n ||
      first_nonpositive_pivot(*factor_) < factor_->n) {
    const auto minor = std::min(factor_->minor, first_nonpositive_pivot(*factor_));
    const int* perm = static_cast<const int*>(factor_->Perm);
    const long dof = (perm && minor < factor_->n) ? perm[minor] : static_cast<long>(minor);
    throw InputError("/structure",
                     fmt::format("the {} matrix is not positive definite: pivot {} of {} fails at "
                                 "DOF {} (0-based). The structure is a mechanism or is missing "
                                 "supports there.",
                                 factors.mass == 0.0 ? "stiffness" : "effective", minor + 1,
                                 factor_->n, dof));
  }
  factorization_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.rail_flexibility && splits_at_rails()) {
    rail_flexibility_from_suffix(model);
  } else if (options.rail_flexibility) {
    compute_rail_flexibility(model, &A);
  }
}

// The rail DOFs are in the factor's suffix: K_bar^-1 there is the inverse
// of the suffix's block (rail_suffix.hpp), no solve of the whole structure.
void CholmodOperator::rail_flexibility_from_suffix(const StructureModel& model) {
  const auto start = std::chrono::steady_clock::now();
  index_rail_dofs(model);
  const DenseMatrix Z = suffix_inverse(*factor_, suffix_start_);
  const int* perm = static_cast<const int*>(factor_->Perm);
  std::vector<int> position(static_cast<std::size_t>(n_));
  for (int k = 0; k < n_; ++k) position[static_cast<std::size_t>(perm[k])] = k - suffix_start_;
  const std::vector<int>& dofs = model.rail_dofs();
  const auto m = static_cast<Eigen::Index>(dofs.size());
  rail_flexibility_.resize(m, m);
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index i = 0; i < m; ++i)
      rail_flexibility_(i, j) = Z(position[static_cast<std::size_t>(dofs[static_cast<std::size_t>(i)])],
                                  position[static_cast<std::size_t>(dofs[static_cast<std::size_t>(j)])]);
  flexibility_solves_ = 0;
  flexibility_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::unique_ptr<SolveWorkspace> CholmodOperator::make_workspace() const {
  return std::make_unique<CholmodWorkspace>();
}

Status CholmodOperator::solve(const Vector& b, Vector& x, SolveWorkspace& ws_base) const {
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  Eigen::Map<DenseMatrix> bmap(const_cast<double*>(b.data()), b.size(), 1);
  if (!ws.solve(factor_.get(), bmap) || !ws.X)
    return {StatusCode::kDiverged, fmt::format("CHOLMOD solve failed (status {})", ws.common.get()->status)};
  x = Eigen::Map<const Vector>(static_cast<const double*>(ws.X->x), n_);
  return Status::Ok();
}

// The split solve (rail_suffix.hpp): P K_bar P^T = L D L^T, forward
// y = (L D)^-1 P b, backward x = P^T L^-T y.
Status CholmodOperator::forward(const Vector& b, Vector& y, SolveWorkspace& ws_base) const {
  if (!splits_at_rails()) return StructureOperator::forward(b, y, ws_base);
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  const int* perm = static_cast<const int*>(factor_->Perm);
  ws.permuted.resize(n_);
  for (int k = 0; k < n_; ++k) ws.permuted[k] = b[perm[k]];
  Eigen::Map<DenseMatrix> bmap(ws.permuted.data(), n_, 1);
  if (!ws.solve(factor_.get(), bmap, CHOLMOD_LD) || !ws.X)
    return {StatusCode::kDiverged, fmt::format("CHOLMOD solve failed (status {})", ws.common.get()->status)};
  y = Eigen::Map<const Vector>(static_cast<const double*>(ws.X->x), n_);
  return Status::Ok();
}

Status CholmodOperator::rail_solution(const Vector& y, Vector& x, SolveWorkspace& ws_base) const {
  if (!splits_at_rails()) return StructureOperator::rail_solution(y, x, ws_base);
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  ws.suffix = y.tail(n_ - suffix_start_);
  suffix_backward(*factor_, suffix_start_, ws.suffix.data());
  const int* perm = static_cast<const int*>(factor_->Perm);
  x.resize(n_);
  for (int k = suffix_start_; k < n_; ++k) x[perm[k]] = ws.suffix[k - suffix_start_];
  return Status::Ok();
}

void CholmodOperator::add_rail_forward(const Vector& load, Vector& y, SolveWorkspace& ws_base) const {
  if (!splits_at_rails()) return StructureOperator::add_rail_forward(load, y, ws_base);
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  const int* perm = static_cast<const int*>(factor_->Perm);
  ws.suffix.resize(n_ - suffix_start_);
  for (int k = suffix_start_; k < n_; ++k) ws.suffix[k - suffix_start_] = load[perm[k]];
  suffix_forward(*factor_, suffix_start_, ws.suffix.data());
  y.tail(n_ - suffix_start_) += ws.suffix;
}

Status CholmodOperator::backward(const Vector& y, Vector& x, SolveWorkspace& ws_base) const {
  if (!splits_at_rails()) return StructureOperator::backward(y, x, ws_base);
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  // cholmod_solve2 reads its right-hand side only, as in solve().
  Eigen::Map<DenseMatrix> ymap(const_cast<double*>(y.data()), n_, 1);
  if (!ws.solve(factor_.get(), ymap, CHOLMOD_Lt) || !ws.X)
    return {StatusCode::kDiverged, fmt::format("CHOLMOD solve failed (status {})", ws.common.get()->status)};
  const double* z = static_cast<const double*>(ws.X->x);
  const int* perm = static_cast<const int*>(factor_->Perm);
  x.resize(n_);
  for (int k = 0; k < n_; ++k) x[perm[k]] = z[k];
  return Status::Ok();
}

DenseMatrix CholmodOperator::inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                                           SolveWorkspace& ws_base) const {
  auto& ws = static_cast<CholmodWorkspace&>(ws_base);
  const auto m = static_cast<Eigen::Index>(rows.size()), nc = static_cast<Eigen::Index>(cols.size());
  DenseMatrix F(m, nc);
  for (Eigen::Index j0 = 0; j0 < nc; j0 += block_columns_) {
    const Eigen::Index nb = std::min<Eigen::Index>(block_columns_, nc - j0);
    DenseMatrix B = DenseMatrix::Zero(n_, nb);
    for (Eigen::Index j = 0; j < nb; ++j) B(cols[j0 + j], j) = 1.0;
    if (!ws.solve(factor_.get(), B) || !ws.X)
      throw InputError("/structure", fmt::format("rail flexibility: CHOLMOD solve failed (status {})",
                                                 ws.common.get()->status));
    const Eigen::Map<const DenseMatrix> X(static_cast<const double*>(ws.X->x), n_, nb);
    for (Eigen::Index j = 0; j < nb; ++j)
      for (Eigen::Index i = 0; i < m; ++i) F(i, j0 + j) = X(rows[i], j);
  }
  return F;
}

std::shared_ptr<const StructureOperator> CholmodOperator::static_operator(const StructureModel& model) const {
  // K's pattern is within K_bar's: the factor of K reuses this one's ordering
  // and symbolic analysis.
  return std::make_shared<const CholmodOperator>(model, EffectiveMatrixFactors{0.0, 0.0, 1.0},
                                                 CholmodOperatorOptions{false, block_columns_}, this);
}

std::size_t CholmodOperator::memory_bytes() const {
  return static_cast<std::size_t>(factor_nonzeros()) * (sizeof(double) + sizeof(int)) +
         static_cast<std::size_t>(rail_flexibility_.size()) * sizeof(double);
}

double CholmodOperator::factor_nonzeros() const {
  if (!factor_->is_super) return static_cast<double>(factor_->nzmax);
  return static_cast<double>(factor_->xsize);
}

}  // namespace railvsi

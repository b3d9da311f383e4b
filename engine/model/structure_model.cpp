#include "model/structure_model.hpp"

#include <algorithm>
#include <map>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {
namespace {

void check_symmetric(const SparseMatrix& A, const std::string& path) {
  const SparseMatrix D = SparseMatrix(A.transpose()) - A;
  double scale = 1.0, worst = 0.0;
  int wr = 0, wc = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) scale = std::max(scale, std::abs(it.value()));
  for (int k = 0; k < D.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(D, k); it; ++it)
      if (std::abs(it.value()) > worst) {
        worst = std::abs(it.value());
        wr = static_cast<int>(it.row());
        wc = static_cast<int>(it.col());
      }
  if (worst > 1e-10 * scale)
    throw InputError(path, fmt::format("matrix is not symmetric: entry ({}, {}) (1-based) differs "
                                       "from its transpose by {:.3e}",
                                       wr + 1, wc + 1, worst));
}

}  // namespace

bool StructureInfo::is_track_dof(int dof) const {
  if (!track_dof_list.empty()) return std::binary_search(track_dof_list.begin(), track_dof_list.end(), dof);
  return dof >= deck_dofs && dof < deck_dofs + track_dofs;
}

StructureModel::StructureModel(SparseMatrix K, SparseMatrix M, SparseMatrix C,
                               std::vector<RailLine> rails, std::vector<OutputPoint> outputs,
                               StructureInfo info)
    : K_(std::move(K)), M_(std::move(M)), C_(std::move(C)), rails_(std::move(rails)),
      outputs_(std::move(outputs)), info_(std::move(info)) {
  const int n = static_cast<int>(K_.rows());
  if (n == 0) throw InputError("/structure", "structure has no free degrees of freedom");
  if (K_.cols() != n || M_.rows() != n || M_.cols() != n)
    throw InputError("/structure", fmt::format("K is {}x{} but M is {}x{}: sizes must agree",
                                               K_.rows(), K_.cols(), M_.rows(), M_.cols()));
  if (C_.rows() == 0) C_.resize(n, n);
  if (C_.rows() != n || C_.cols() != n)
    throw InputError("/structure/C", "damping matrix size differs from K");
  K_.makeCompressed();
  M_.makeCompressed();
  C_.makeCompressed();
  check_symmetric(K_, "/structure/K");
  check_symmetric(M_, "/structure/M");
  check_symmetric(C_, "/structure/C");
  const Vector mdiag = M_.diagonal();
  for (int i = 0; i < n; ++i)
    if (!(mdiag[i] >= 0.0) || !std::isfinite(mdiag[i]))
      throw InputError("/structure/M", fmt::format("mass matrix diagonal at DOF {} (1-based) is {} "
                                                   "(must be >= 0)", i + 1, mdiag[i]));
  if (mdiag.sum() <= 0.0) throw InputError("/structure/M", "mass matrix has no positive mass");

  if (rails_.empty()) throw InputError("/structure/rail_lines", "at least one rail line is needed");
  for (std::size_t r = 0; r < rails_.size(); ++r) {
    const RailLine& line = rails_[r];
    const std::string path = fmt::format("/structure/rail_lines/{}", r);
    if (line.x_m.size() < 2) throw InputError(path, "a rail line needs at least two nodes");
    if (line.element_dofs.size() + 1 != line.x_m.size())
      throw InputError(path, "x_m, dof_v and dof_rot must have the same length");
    for (std::size_t i = 1; i < line.x_m.size(); ++i)
      if (!(line.x_m[i] > line.x_m[i - 1]))
        throw InputError(fmt::format("{}/x_m/{}", path, i),
                         fmt::format("rail node x must increase strictly ({} after {})",
                                     line.x_m[i], line.x_m[i - 1]));
    // Element e holds nodes e and e + 1 ({v, rot} of each): every DOF is
    // named at its own entry, and one DOF at two nodes (or as both v and
    // rot) is refused. A node may have two DOFs of one kind (a hinge: the
    // two elements' ends differ).
    std::map<int, std::string> seen;  // DOF -> "dof_v/i" or "dof_rot/i"
    for (std::size_t e = 0; e < line.element_dofs.size(); ++e)
      for (std::size_t k = 0; k < 4; ++k) {
        const int d = line.element_dofs[e][k];
        const std::string entry = fmt::format("{}/{}", k % 2 == 0 ? "dof_v" : "dof_rot", e + k / 2);
        if (d < -1 || d >= n)
          throw InputError(fmt::format("{}/{}", path, entry),
                           fmt::format("equation {} outside the model (0..{}; -1 for a fixed DOF)", d, n - 1));
        if (d < 0) continue;
        if (const auto [it, fresh] = seen.emplace(d, entry); !fresh && it->second != entry)
          throw InputError(fmt::format("{}/{}", path, entry),
                           fmt::format("equation {} is on this rail line twice (also at {}): each node needs DOFs "
                                       "of its own",
                                       d, it->second));
        rail_dofs_.push_back(d);
      }
  }
  std::sort(rail_dofs_.begin(), rail_dofs_.end());
  rail_dofs_.erase(std::unique(rail_dofs_.begin(), rail_dofs_.end()), rail_dofs_.end());
  for (std::size_t p = 0; p < outputs_.size(); ++p)
    if (outputs_[p].dof < 0 || outputs_[p].dof >= n)
      throw InputError(fmt::format("/structure/output_points/{}", p),
                       fmt::format("output point DOF {} outside the model", outputs_[p].dof));
}

}  // namespace railvsi

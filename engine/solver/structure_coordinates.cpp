#include "solver/structure_coordinates.hpp"

#include <limits>

namespace railvsi {
namespace {

SparseMatrix diagonal(const std::vector<double>& d) {
  SparseMatrix D(static_cast<Eigen::Index>(d.size()), static_cast<Eigen::Index>(d.size()));
  std::vector<Triplet> t;
  for (std::size_t i = 0; i < d.size(); ++i) t.emplace_back(static_cast<int>(i), static_cast<int>(i), d[i]);
  D.setFromTriplets(t.begin(), t.end());
  D.makeCompressed();
  return D;
}

}  // namespace

StructureCoordinates::StructureCoordinates(const StructureModel& model)
    : size_(model.num_dofs()), model_dofs_(model.num_dofs()), M_(&model.M()), C_(&model.C()), K_(&model.K()) {}

StructureCoordinates::StructureCoordinates(std::shared_ptr<const ModalBasis> basis)
    : basis_(std::move(basis)), size_(basis_->num_modes()), model_dofs_(basis_->structure().num_dofs()) {
  const auto& w = basis_->omega_rad_s();
  std::vector<double> one(w.size(), 1.0), c(w.size()), k(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    c[i] = 2.0 * basis_->zeta()[i] * w[i];
    k[i] = w[i] * w[i];
  }
  modal_M_ = diagonal(one);
  modal_C_ = diagonal(c);
  modal_K_ = diagonal(k);
}

StructureCoordinates::StructureCoordinates(std::shared_ptr<const HybridBasis> hybrid)
    : hybrid_(std::move(hybrid)), size_(hybrid_->size()), model_dofs_(hybrid_->structure().num_dofs()),
      M_(&hybrid_->reduced().M()), C_(&hybrid_->reduced().C()), K_(&hybrid_->reduced().K()) {}

double StructureCoordinates::hybrid_at(int dof, const Vector& x) const {
  if (const int i = hybrid_->index(dof); i >= 0) return x[i];
  const double* row = hybrid_->row(dof);
  if (!row) return std::numeric_limits<double>::quiet_NaN();
  const int n = hybrid_->interface_dofs() + hybrid_->num_modes();
  return Eigen::Map<const Vector>(row, n).dot(x.segment(hybrid_->track_dofs(), n));
}

void StructureCoordinates::hybrid_add(int dof, double f, Vector& x) const {
  if (const int i = hybrid_->index(dof); i >= 0) {
    x[i] += f;
    return;
  }
  const double* row = hybrid_->row(dof);
  const int n = hybrid_->interface_dofs() + hybrid_->num_modes();
  if (row) x.segment(hybrid_->track_dofs(), n) += f * Eigen::Map<const Vector>(row, n);
  else x.setConstant(std::numeric_limits<double>::quiet_NaN());  // a load where none can act: never silent
}

double StructureCoordinates::max_abs_displacement(const Vector& x) const {
  if (x.size() == 0) return 0.0;
  if (hybrid_) {
    // The track and the interface; the interior's largest is near them
    // (constraint modes) or at an output point, which the monitor reads.
    const int n = hybrid_->track_dofs() + hybrid_->interface_dofs();
    return n > 0 ? x.head(n).cwiseAbs().maxCoeff() : 0.0;
  }
  if (!basis_) return x.cwiseAbs().maxCoeff();
  return (basis_->kept_rows().transpose() * x).cwiseAbs().maxCoeff();
}

double row_value(const std::optional<RailContactRow>& row, std::array<double, 4> RailContactRow::*w,
                 const Vector& u, const StructureCoordinates& coords) {
  if (!row) return 0.0;
  double z = 0.0;
  for (int k = 0; k < 4; ++k)
    if (row->dof[k] >= 0) z += ((*row).*w)[k] * coords.at(row->dof[k], u);
  return z;
}

double rail_top(const std::optional<RailContactRow>& row, const Vector& u, const StructureCoordinates& coords) {
  return row_value(row, &RailContactRow::weight, u, coords);
}

void add_rail_loads(const std::vector<std::optional<RailContactRow>>& rows, const Vector& P, double scale,
                    Vector& f, const StructureCoordinates& coords) {
  for (std::size_t c = 0; c < rows.size(); ++c) {
    if (!rows[c]) continue;
    for (int k = 0; k < 4; ++k)
      if (rows[c]->dof[k] >= 0)
        coords.add(rows[c]->dof[k], -scale * rows[c]->weight[k] * P[static_cast<Eigen::Index>(c)], f);
  }
}

}  // namespace railvsi

#pragma once
// The coordinates a structure backend integrates the structure in, and how
// they map to the model's DOFs: the DOFs themselves (finite elements), or
// the modal coordinates q of a ModalBasis with u = Phi q (the modal rung:
// M = I, C = diag(2 zeta omega), K = diag(omega^2) in q). Everything that
// reads the structure's state at a DOF (the rail top under a wheel, a deck
// output) or loads it at a DOF (a wheel or axle load) goes through here, so
// the time loop is written once for both. The hybrid structure's
// coordinates are [u_track; u_interface; q] (HybridBasis): a track or
// interface DOF is read directly, a bridge DOF inside through its row.
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/types.hpp"
#include "model/rail_line.hpp"
#include "model/structure_model.hpp"
#include "solver/hybrid_basis.hpp"
#include "solver/modal_basis.hpp"

namespace railvsi {

class StructureCoordinates {
 public:
  // The model's own DOFs (finite elements).
  explicit StructureCoordinates(const StructureModel& model);
  // Modal coordinates of `basis`: the rows of Phi it keeps (rail and output
  // DOFs) are all that is ever read.
  explicit StructureCoordinates(std::shared_ptr<const ModalBasis> basis);
  // The hybrid structure's reduced coordinates.
  explicit StructureCoordinates(std::shared_ptr<const HybridBasis> hybrid);

  bool modal() const { return basis_ != nullptr; }
  bool hybrid() const { return hybrid_ != nullptr; }
  // Length of a state vector.
  int size() const { return size_; }
  // DOFs of the model the coordinates describe.
  int model_dofs() const { return model_dofs_; }
  // The structure's matrices in these coordinates (the model's own for
  // finite elements). Valid while the model (FE), the hybrid basis or
  // this object (modes) lives.
  const SparseMatrix& M() const { return basis_ ? modal_M_ : *M_; }
  const SparseMatrix& C() const { return basis_ ? modal_C_ : *C_; }
  const SparseMatrix& K() const { return basis_ ? modal_K_ : *K_; }

  // Displacement (velocity, acceleration) at a model DOF of the state x; 0
  // for a fixed DOF (-1). NaN for a bridge DOF the hybrid structure does
  // not keep (a run never reads one: HybridBasis keeps what runs read).
  double at(int dof, const Vector& x) const {
    if (dof < 0) return 0.0;
    if (hybrid_) return hybrid_at(dof, x);
    if (!basis_) return x[dof];
    return Eigen::Map<const Vector>(basis_->row(dof), size_).dot(x);
  }
  // x += the load f at a model DOF, in these coordinates (Phi^T f for modes).
  void add(int dof, double f, Vector& x) const {
    if (dof < 0) return;
    if (hybrid_) return hybrid_add(dof, f, x);
    if (!basis_) {
      x[dof] += f;
      return;
    }
    x += f * Eigen::Map<const Vector>(basis_->row(dof), size_);
  }
  // Largest |displacement| of the state x: over all DOFs (FE), over the kept
  // rail and output DOFs (modes); for the run monitor's plausibility check.
  double max_abs_displacement(const Vector& x) const;

 private:
  double hybrid_at(int dof, const Vector& x) const;
  void hybrid_add(int dof, double f, Vector& x) const;
  std::shared_ptr<const ModalBasis> basis_;
  std::shared_ptr<const HybridBasis> hybrid_;
  int size_ = 0;
  int model_dofs_ = 0;
  const SparseMatrix* M_ = nullptr;  // the model's (FE, hybrid: the reduced one)
  const SparseMatrix* C_ = nullptr;
  const SparseMatrix* K_ = nullptr;
  SparseMatrix modal_M_, modal_C_, modal_K_;  // diagonal (modes)
};

// sum_k w[k] u[dof[k]] over a Hermite row (0 on the rigid path).
double row_value(const std::optional<RailContactRow>& row, std::array<double, 4> RailContactRow::*w,
                 const Vector& u, const StructureCoordinates& coords);
// The rail top N u under a located contact (0 on the rigid path).
double rail_top(const std::optional<RailContactRow>& row, const Vector& u, const StructureCoordinates& coords);
// Adds -scale * N_k^T P_k to f for every on-track load.
void add_rail_loads(const std::vector<std::optional<RailContactRow>>& rows, const Vector& P, double scale,
                    Vector& f, const StructureCoordinates& coords);

}  // namespace railvsi

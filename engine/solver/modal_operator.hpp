#pragma once
// Modal backend of the structure: the structure replaced by its modes up to
// a cut-off (ModalBasis), state = modal coordinates q with M = I,
// C = diag(2 zeta omega), K = diag(omega^2). Each mode is integrated by the
// same HHT scheme as the vehicles, so that structure and vehicles are
// coupled consistently by the condensed direct method: K_bar is diagonal,
// K_bar^-1 = D, and the rail flexibility is A = Phi_r D Phi_r^T (Phi_r: the
// rows of the modes at the rail DOFs). What it gives up against the FE
// backend: the modes above the cut-off, and the coupling terms of a
// non-proportional damping matrix. With the static correction (default),
// the dropped modes keep their static part at the rail DOFs: the contact
// sees A + R (rail_residual_flexibility(); README "The modal structure").
#include <memory>

#include "solver/modal_basis.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

struct ModalOperatorOptions {
  bool rail_flexibility = true;
  // The residual static flexibility of the dropped modes at the rail DOFs
  // (ModalBasis::rail_residual_flexibility(): a factor of K, once per
  // basis). The factory asks for it with the rail flexibility only (a
  // multibody train); static_operator() inherits it.
  bool static_correction = true;
};

class ModalOperator final : public StructureOperator {
 public:
  // Throws InputError when a mode has no positive effective stiffness (a
  // rigid-body mode in the static operator).
  ModalOperator(std::shared_ptr<const ModalBasis> basis, const EffectiveMatrixFactors& factors,
                const ModalOperatorOptions& options = {});

  int num_dofs() const override { return basis_->num_modes(); }
  std::unique_ptr<SolveWorkspace> make_workspace() const override { return std::make_unique<SolveWorkspace>(); }
  Status solve(const Vector& b, Vector& x, SolveWorkspace& ws) const override;
  DenseMatrix inverse_block(const std::vector<int>& rows, const std::vector<int>& cols,
                            SolveWorkspace& ws) const override;
  std::string backend_name() const override;
  StructureCoordinates coordinates(const StructureModel& model) const override;
  std::shared_ptr<const StructureOperator> static_operator(const StructureModel& model) const override;
  std::size_t memory_bytes() const override;
  const ModalBasis& basis() const { return *basis_; }
  const DenseMatrix* rail_residual_flexibility() const override { return residual_; }

 private:
  std::shared_ptr<const ModalBasis> basis_;
  const DenseMatrix* residual_ = nullptr;  // the basis's, or null
  Vector d_;  // K_bar^-1, diagonal
};

}  // namespace railvsi

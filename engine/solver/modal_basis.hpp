#pragma once
// The modes of a structure up to a cut-off, computed once and shared by
// every run on that structure (immutable, safe across threads): natural
// frequencies, modal damping ratios, and the mode shapes where runs read
// them: at the rail DOFs (for the loads) and at the output points.
#include <memory>
#include <mutex>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/modal_analysis.hpp"

namespace railvsi {

struct ModalBasisOptions {
  // All modes up to this frequency (Hz) are kept; > 0.
  double max_frequency_hz = 60.0;
  // Never fewer than this many modes (when the structure has them).
  int min_modes = 1;
};

class ModalBasis {
 public:
  // modal_analysis of K, M with the cut-off, in one solve. Throws InputError when the modes
  // cannot be computed.
  ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalBasisOptions& options);
  // Modes computed elsewhere (mass-normalised shapes, one column per mode,
  // ascending frequencies), e.g. all of a small model's from a dense
  // eigensolver; the cut-off is the highest frequency.
  ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalResult& modes);

  const StructureModel& structure() const { return *structure_; }
  int num_modes() const { return static_cast<int>(omega_.size()); }
  double max_frequency_hz() const { return max_frequency_hz_; }
  const std::vector<double>& omega_rad_s() const { return omega_; }
  // phi_k^T C phi_k / (2 omega_k): exact for Rayleigh damping; for another
  // C the coupling terms between modes are left out.
  const std::vector<double>& zeta() const { return zeta_; }
  // Mass-normalised shapes at one DOF (a row of Phi), kept for the rail and
  // output DOFs (and every DOF of a beam deck, for its section forces);
  // zero for a fixed DOF (-1) and any other DOF.
  const double* row(int dof) const;
  // The kept rows (rail DOFs first, then output DOFs not on a rail), one
  // column per DOF.
  const DenseMatrix& kept_rows() const { return rail_shapes_; }
  // Shapes at the output points, one row per point.
  const DenseMatrix& at_outputs() const { return at_outputs_; }
  // What the basis holds in memory (the structure it shares excepted, and
  // the residual flexibility: its operators count that).
  std::size_t memory_bytes() const;
  // The static flexibility of the modes left out, at the rail DOFs
  // (StructureModel::rail_dofs() order; residual_flexibility.hpp). Computed
  // at the first call (a factor of K and the rail columns of its inverse),
  // then shared by every operator on this basis, for every dt; safe to call
  // from several threads. Throws InputError when K cannot be factorized.
  const DenseMatrix& rail_residual_flexibility() const;
  // The same between the output points and the rail DOFs: row i holds the
  // static displacement of output point i under a unit force at each rail
  // DOF (StructureModel::rail_dofs() order) that the kept modes leave out,
  // e_i^T K^-1 - Phi_i Omega^-2 Phi_r^T. Under the loads of a moving train
  // it adds to the outputs the quasi-static response of the dropped modes
  // (the static correction of the mode-acceleration method). Computed at
  // the first call from one factor of K and one solve per output point,
  // then shared; safe from several threads. Throws InputError when K
  // cannot be factorized.
  const DenseMatrix& output_residual_flexibility() const;

 private:
  void set_modes(const ModalResult& modes);
  std::shared_ptr<const StructureModel> structure_;
  double max_frequency_hz_ = 0.0;
  std::vector<double> omega_, zeta_;
  // Rows of Phi kept for the rail and output DOFs, by structure DOF.
  std::vector<int> rail_row_;  // DOF -> row in rail_shapes_, -1 otherwise
  DenseMatrix rail_shapes_;    // row-major in effect: one row per kept DOF (stored transposed)
  std::vector<double> zero_row_;
  DenseMatrix at_outputs_;
  // A cache filled once, not state: the basis stays immutable in meaning.
  mutable std::once_flag residual_once_;
  mutable DenseMatrix residual_;
  mutable std::once_flag output_residual_once_;
  mutable DenseMatrix output_residual_;
};

}  // namespace railvsi

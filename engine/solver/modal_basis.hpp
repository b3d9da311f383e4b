#pragma once
// The modes of a structure up to a cut-off, computed once and shared by
// every run on that structure (immutable, safe across threads): natural
// frequencies, modal damping ratios, and the mode shapes where runs read
// them: at the rail DOFs (for the loads) and at the output points.
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

struct ModalBasisOptions {
  // All modes up to this frequency (Hz) are kept; > 0.
  double max_frequency_hz = 60.0;
  // Never fewer than this many modes (when the structure has them).
  int min_modes = 1;
};

class ModalBasis {
 public:
  // Lanczos on K, M (modal_analysis). Throws InputError when the modes
  // cannot be computed.
  ModalBasis(std::shared_ptr<const StructureModel> structure, const ModalBasisOptions& options);

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
  // What the basis holds in memory (the structure it shares excepted).
  std::size_t memory_bytes() const;

 private:
  std::shared_ptr<const StructureModel> structure_;
  double max_frequency_hz_ = 0.0;
  std::vector<double> omega_, zeta_;
  // Rows of Phi kept for the rail and output DOFs, by structure DOF.
  std::vector<int> rail_row_;  // DOF -> row in rail_shapes_, -1 otherwise
  DenseMatrix rail_shapes_;    // row-major in effect: one row per kept DOF (stored transposed)
  std::vector<double> zero_row_;
  DenseMatrix at_outputs_;
};

}  // namespace railvsi

#pragma once
// The hybrid structure: the track in finite elements, the bridge in its
// modes. The bridge DOFs split into the interface G (those coupled to a
// track DOF in K, M or C) and the interior I, and
//
//   u_I = Psi u_G + Phi q,   Psi = -K_II^-1 K_IG,
//
// Psi the static constraint modes and Phi a basis of the interior with the
// interface held: by default the bridge's own modes up to a cut-off (its
// interface free), less their static interface part (BridgeModes::
// kFreeInterface, MacNeal-Rubin in primal form), or the interior's modes
// with the interface held (kFixedInterface, Craig & Bampton, "Coupling of
// substructures for dynamic analyses", AIAA Journal 6(7), 1968). The state
// is x = [u_T; u_G; q]: the track's DOFs and the interface as they are, the
// interior in its modes. The reduced matrices are T' K T, T' M T, T' C T of
// that transformation, so the track keeps its own damping and its coupling
// to the deck exactly, and the constraint modes hold the static response
// of every interior mode left out: loads act on the track only, so the
// reduction is statically exact whatever the cut-off. With every interior
// mode kept it is the finite-element model in other coordinates.
//
// Immutable once built, shared by the operators of every dt.
#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// How the hybrid structure would split a model, without computing anything
// else (a scan of K, M and C): for the planner's choice and the messages.
struct HybridPartition {
  int track_dofs = 0;
  int interface_dofs = 0;  // bridge DOFs coupled to a track DOF
  int interior_dofs = 0;   // the rest of the bridge, which the modes replace
  // Why the hybrid structure cannot be built ("" when it can): no track, or
  // a rail on a bridge DOF.
  std::string unavailable;
};
HybridPartition hybrid_partition(const StructureModel& structure);

// Which modes of the bridge join its static constraint modes.
enum class BridgeModes {
  // The interior's modes with the interface held, K_II phi = omega^2 M_II
  // phi (Craig-Bampton).
  kFixedInterface,
  // The bridge's own modes without its track, the interface free
  // (K_BB phi = omega^2 M_BB phi), each less its static interface part:
  // phi_I - Psi phi_G. With the constraint modes they span what
  // free-interface modes with residual flexibility span (MacNeal-Rubin in
  // primal form: MacNeal, Computers & Structures 1(4), 1971; Rubin, AIAA
  // Journal 13(8), 1975). The bridge's low modes are then in the basis as
  // they are, where the held interface (the deck's top, which carries the
  // track) moves the fixed-interface modes far above them.
  kFreeInterface,
};

struct HybridBasisOptions {
  // Interior modes up to this frequency (Hz), > 0; or, when modes > 0,
  // exactly the lowest `modes`; or, with all_modes, every one (a dense
  // eigensolver: small models, for verification).
  double max_frequency_hz = 0.0;
  int modes = 0;
  bool all_modes = false;
  // Interface columns per block of the constraint modes' solve and of the
  // reduction's products: the dense work arrays are a block wide.
  int column_block = 128;
  // When the bridge's interior is damped as a0 M + a1 K (to
  // kRayleighFitTolerance), reduce C from M's and K's reductions instead
  // of its own products (false: always its own; for verification).
  bool rayleigh_shortcut = true;
  BridgeModes bridge_modes = BridgeModes::kFreeInterface;
  // Free-interface modes: the constraint modes from one factor of the whole
  // bridge with the interface last, which is also the modes' first shift
  // (interface_last_factor.hpp); false: from a factor of K_II, the modes
  // with a factor of their own (for verification).
  bool interface_last_factor = true;
};

// How exactly C must equal a0 M + a1 K on the bridge's interior (largest
// entry of the difference over C's largest there) for the shortcut.
inline constexpr double kRayleighFitTolerance = 1e-12;

// What the reduction cost, by part (CPU seconds of the building thread).
struct HybridBasisSummary {
  double constraint_modes_cpu_s = 0.0;  // K_II's factor and Psi
  double interior_modes_cpu_s = 0.0;    // the modes with the interface held
  double interior_factor_cpu_s = 0.0;   // of which the mode solver's factors
  double reduction_cpu_s = 0.0;         // T' K T, T' M T, T' C T
  int factorizations = 0;               // of the mode solver (its first shift is the constraint modes' factor)
  // The free-interface modes' first shift was the constraint modes' factor
  // of the whole bridge with the interface last (interface_last_factor.hpp),
  // not a factor of their own.
  bool shared_bridge_factor = false;
  // The interior modes come from block Lanczos: the largest true relative
  // residual of its pairs and of those kept, and whether its pairs failed
  // kMaxBlockLanczosResidual (ModalResult) and were computed again one
  // vector at a time. Zero when the interior is solved densely.
  double interior_block_residual = 0.0;
  double interior_max_residual = 0.0;
  bool interior_single_vector_fallback = false;
  // C was reduced from M's and K's reductions (HybridBasisOptions::
  // rayleigh_shortcut and a Rayleigh-damped interior).
  bool rayleigh_damping = false;
};


class HybridBasis {
 public:
  // Throws InputError when the structure has no track, when a rail DOF is
  // not a track DOF, or when the interior's modes cannot be computed.
  HybridBasis(std::shared_ptr<const StructureModel> structure, const HybridBasisOptions& options);

  const StructureModel& structure() const { return *structure_; }
  // The reduced model: K, M, C in x = [u_T; u_G; q], the rail lines on
  // their track DOFs, no output points (they are read through row()).
  const StructureModel& reduced() const { return *reduced_; }

  int track_dofs() const { return n_track_; }
  int interface_dofs() const { return n_interface_; }
  int num_modes() const { return static_cast<int>(frequencies_hz_.size()); }
  int size() const { return n_track_ + n_interface_ + num_modes(); }
  // Frequencies of the interior's modes kept (interface held), ascending:
  // with free-interface modes, those of the interior in the subspace they
  // span (Rayleigh-Ritz).
  const std::vector<double>& frequencies_hz() const { return frequencies_hz_; }
  // With free-interface modes, the bridge's own frequencies that the
  // cut-off chose (interface free); empty otherwise.
  const std::vector<double>& bridge_frequencies_hz() const { return bridge_frequencies_hz_; }
  BridgeModes bridge_modes() const { return bridge_modes_; }
  // "free-interface " for free-interface modes, "" for the interface held
  // (the form the fidelity records have named since the hybrid rung came).
  const char* modes_label() const { return bridge_modes_ == BridgeModes::kFreeInterface ? "free-interface " : ""; }
  // The cut-off asked, or the highest frequency kept (modes, all_modes).
  double cutoff_hz() const { return cutoff_hz_; }

  // The coordinate of a track or interface DOF, -1 for an interior DOF or
  // a fixed one (-1).
  int index(int dof) const { return dof < 0 ? -1 : index_[static_cast<std::size_t>(dof)]; }
  // An interior DOF as a combination of [u_G; q] (interface_dofs() +
  // num_modes() values, starting at coordinate track_dofs()): kept for the
  // output points, and every interior DOF of a beam deck (section forces).
  // Null for another DOF.
  const double* row(int dof) const;
  bool has_row(int dof) const { return dof >= 0 && row_of_[static_cast<std::size_t>(dof)] >= 0; }
  std::size_t memory_bytes() const;
  const HybridBasisSummary& summary() const { return summary_; }
  std::string describe() const;

 private:
  std::shared_ptr<const StructureModel> structure_;
  std::shared_ptr<const StructureModel> reduced_;
  int n_track_ = 0, n_interface_ = 0;
  std::vector<double> frequencies_hz_;
  std::vector<double> bridge_frequencies_hz_;
  BridgeModes bridge_modes_ = BridgeModes::kFreeInterface;
  double cutoff_hz_ = 0.0;
  std::vector<int> index_;   // model DOF -> coordinate, -1 interior
  std::vector<int> row_of_;  // model DOF -> column of rows_, -1 none
  DenseMatrix rows_;         // one column per kept interior DOF
  HybridBasisSummary summary_;
};

}  // namespace railvsi

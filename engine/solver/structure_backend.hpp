#pragma once
// The one place a structure backend is chosen: a StructureOperator created
// from options (as Ceres' SparseCholesky::Create does for its sparse
// solvers). Backends: finite elements (a CHOLMOD factor of K_bar) and modal
// (the modes up to a cut-off, diagonal K_bar) and hybrid (the track in
// finite elements, the bridge in its modes: hybrid_basis.hpp).
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solver/hybrid_basis.hpp"
#include "solver/modal_basis.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

enum class StructureBackend { kFiniteElements, kModal, kHybrid };

// The modal cut-off when a scene names neither modes nor a cut-off.
inline constexpr double kDefaultModalCutoffHz = 100.0;

struct StructureOperatorOptions {
  StructureBackend structure_backend = StructureBackend::kFiniteElements;
  // Modal: this many modes (the lowest) when > 0; else every mode up to
  // modal_cutoff_hz, or up to kDefaultModalCutoffHz when that is 0 too.
  // Hybrid: the same for the bridge's modes with the track held.
  int modal_modes = 0;
  double modal_cutoff_hz = 0.0;
  // Hybrid: which modes of the bridge (hybrid_basis.hpp).
  BridgeModes hybrid_bridge_modes = BridgeModes::kFreeInterface;
  bool rail_flexibility = true;
  // Modal, with rail_flexibility: add the static flexibility of the dropped
  // modes at the rail DOFs to the contact's (ModalOperatorOptions).
  bool modal_static_correction = true;
  int flexibility_block_columns = 64;  // FE: right-hand sides per blocked solve
  // FE: order the rail DOFs last when this adds at most this fraction of
  // the factor's nonzeros, for one solve per step (rail_suffix.hpp); 0: never.
  double rails_last_max_fill_growth = 0.10;
  // Modal: modes computed before (of the same structure, for the same
  // options), shared between operators for several dt; computed when null.
  std::shared_ptr<const ModalBasis> modal_basis = nullptr;
  // Hybrid: the reduction computed before (same structure, same modes),
  // shared between operators for several dt; computed when null.
  std::shared_ptr<const HybridBasis> hybrid_basis = nullptr;
};

// The modes the options ask for (modal_modes, modal_cutoff_hz). Throws
// InputError when they cannot be computed.
std::shared_ptr<const ModalBasis> make_modal_basis(std::shared_ptr<const StructureModel> model,
                                                   const StructureOperatorOptions& options);

// The hybrid reduction the options ask for (modal_modes, modal_cutoff_hz
// for the bridge's modes). Throws InputError as HybridBasis does.
std::shared_ptr<const HybridBasis> make_hybrid_basis(std::shared_ptr<const StructureModel> model,
                                                     const StructureOperatorOptions& options);

// Throws InputError when the structure cannot be factorized (a mechanism)
// or its modes cannot be computed.
std::shared_ptr<const StructureOperator> make_structure_operator(std::shared_ptr<const StructureModel> model,
                                                                 const EffectiveMatrixFactors& factors,
                                                                 const StructureOperatorOptions& options);

// "fe", "modal" or "hybrid", as scenes name them (analysis.schema.json):
// the one spelling of a backend in scenes, records and the price table.
const char* structure_backend_name(StructureBackend backend);
// nullopt for a name that is none of structure_backend_names().
std::optional<StructureBackend> parse_structure_backend(std::string_view name);
std::vector<std::string> structure_backend_names();

}  // namespace railvsi

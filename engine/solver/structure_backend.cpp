#include "solver/structure_backend.hpp"

#include <limits>

#include "core/input_error.hpp"
#include "solver/cholmod_operator.hpp"
#include "solver/hybrid_operator.hpp"
#include "solver/modal_operator.hpp"

namespace railvsi {

std::shared_ptr<const ModalBasis> make_modal_basis(std::shared_ptr<const StructureModel> model,
                                                   const StructureOperatorOptions& options) {
  ModalBasisOptions mo;
  if (options.modal_modes > 0) {
    // Exactly the lowest modal_modes: none is kept for its frequency.
    mo.min_modes = options.modal_modes;
    mo.max_frequency_hz = std::numeric_limits<double>::min();
  } else {
    mo.max_frequency_hz = options.modal_cutoff_hz > 0.0 ? options.modal_cutoff_hz : kDefaultModalCutoffHz;
  }
  return std::make_shared<const ModalBasis>(std::move(model), mo);
}

std::shared_ptr<const HybridBasis> make_hybrid_basis(std::shared_ptr<const StructureModel> model,
                                                     const StructureOperatorOptions& options) {
  HybridBasisOptions ho;
  ho.modes = options.modal_modes;
  ho.max_frequency_hz = options.modal_cutoff_hz > 0.0 ? options.modal_cutoff_hz : kDefaultModalCutoffHz;
  ho.bridge_modes = options.hybrid_bridge_modes;
  return std::make_shared<const HybridBasis>(std::move(model), ho);
}

std::shared_ptr<const StructureOperator> make_structure_operator(std::shared_ptr<const StructureModel> model,
                                                                 const EffectiveMatrixFactors& factors,
                                                                 const StructureOperatorOptions& options) {
  switch (options.structure_backend) {
    case StructureBackend::kFiniteElements:
      return std::make_shared<const CholmodOperator>(
          *model, factors,
          CholmodOperatorOptions{options.rail_flexibility, options.flexibility_block_columns,
                                 options.rails_last_max_fill_growth});
    case StructureBackend::kModal: {
      auto basis = options.modal_basis ? options.modal_basis : make_modal_basis(model, options);
      if (basis->structure().num_dofs() != model->num_dofs())
        throw InputError("/structure", "the modal basis was computed for another structure");
      return std::make_shared<const ModalOperator>(std::move(basis), factors,
                                                   ModalOperatorOptions{options.rail_flexibility,
                                                                        options.rail_flexibility &&
                                                                            options.modal_static_correction});
    }
    case StructureBackend::kHybrid: {
      auto basis = options.hybrid_basis ? options.hybrid_basis : make_hybrid_basis(model, options);
      if (basis->structure().num_dofs() != model->num_dofs())
        throw InputError("/structure", "the hybrid reduction was computed for another structure");
      return std::make_shared<const HybridOperator>(
          std::move(basis), factors,
          CholmodOperatorOptions{options.rail_flexibility, options.flexibility_block_columns,
                                 options.rails_last_max_fill_growth});
    }
  }
  throw InputError("/analysis/structure", "unknown structure backend");
}

const char* structure_backend_name(StructureBackend backend) {
  switch (backend) {
    case StructureBackend::kModal:
      return "modal";
    case StructureBackend::kHybrid:
      return "hybrid";
    case StructureBackend::kFiniteElements:
      break;
  }
  return "fe";
}

std::optional<StructureBackend> parse_structure_backend(std::string_view name) {
  for (const StructureBackend b : {StructureBackend::kFiniteElements, StructureBackend::kModal, StructureBackend::kHybrid})
    if (name == structure_backend_name(b)) return b;
  return std::nullopt;
}

std::vector<std::string> structure_backend_names() {
  return {structure_backend_name(StructureBackend::kFiniteElements), structure_backend_name(StructureBackend::kModal),
          structure_backend_name(StructureBackend::kHybrid)};
}

}  // namespace railvsi

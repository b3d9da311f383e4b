#include "workers/cached_operator.hpp"

#include "simulation/simulation.hpp"
#include "study/structure_key.hpp"

namespace railvsi::scheduler {

CacheLookup cached_operator(FactorizationCache& cache, const std::string& key, const std::string& structure_part,
                            const Scene& scene, std::shared_ptr<const HybridBasis> reuse) {
  HybridBasisLookup reduction;
  if (!reuse && scene.analysis.structure_backend == StructureBackend::kHybrid) {
    reduction = cache.get_hybrid_basis(hybrid_basis_key(structure_part, *scene.structure, scene.analysis.modal_modes,
                                                        scene.analysis.modal_cutoff_hz),
                                       [&] { return make_hybrid_basis(scene); });
    reuse = reduction.basis;
  }
  CacheLookup lookup = cache.get(key, [&] { return make_structure_operator(scene, nullptr, reuse); });
  lookup.factorized = lookup.factorized || reduction.built;
  lookup.factorization_s += reduction.build_s;
  lookup.evictions += reduction.evictions;
  return lookup;
}

}  // namespace railvsi::scheduler

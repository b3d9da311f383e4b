#pragma once
// A scene's structure operator taken from a worker process's cache, or built
// into it: the one way jobs (and vsi run's dry run at submission) get one.
#include <memory>
#include <string>

#include "simulation/scene.hpp"
#include "solver/hybrid_basis.hpp"
#include "workers/factorization_cache.hpp"

namespace railvsi::scheduler {

// The operator of `scene` under `key` (its operator key, or a key derived
// from it for another dt or backend). On the hybrid structure its reduction
// is `reuse` when given, else taken from the cache under hybrid_basis_key
// of `structure_part` (the reduction does not depend on dt: a study's
// speeds and its dt/2 verification runs share one), else built. The
// lookup counts what this call built: the operator and the reduction.
CacheLookup cached_operator(FactorizationCache& cache, const std::string& key, const std::string& structure_part,
                            const Scene& scene, std::shared_ptr<const HybridBasis> reuse = nullptr);

}  // namespace railvsi::scheduler

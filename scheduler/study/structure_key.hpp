#pragma once
// Content keys of what jobs may share: the structure model (its matrices and
// rail DOFs), and the factorization of K_bar for a time step.
#include <string>

#include "model/structure_model.hpp"
#include "simulation/scene.hpp"

namespace railvsi::scheduler {

// SHA-256 of K, M, C (pattern and values) and the rail DOFs. Two structures
// with the same hash have the same K_bar for every dt: the key does not
// depend on how the structure was described (a generator or an import, an
// approach embankment sized by the train or given).
std::string structure_model_hash(const StructureModel& structure);

// The factorization cache key: structure hash, dt, HHT alpha/beta/gamma and
// whether the rail flexibility block is needed (multibody trains). Written
// "<structure hash>/<SHA-256 of the rest>": what does not depend on dt (an
// imported model, the hybrid structure's reduction) is shared by the keys
// with the same structure part.
std::string operator_key(const std::string& structure_hash, const AnalysisOptions& analysis, bool rail_flexibility);

// The key of a modal basis and the pass built on it (modal moving forces):
// the structure hash, its rail lines (node x and element DOFs) and output
// points (name, x, DOF), which the run reads from the basis's structure,
// the modal cut-off and dt.
std::string modal_operator_key(const std::string& structure_hash, const StructureModel& structure, double cutoff_hz,
                               double dt_s);

// The structure hash an operator key starts with; a key without one (made
// before keys had it: a store's older jobs) is its own structure part.
std::string structure_part(const std::string& operator_key);

// The key of a hybrid structure's reduction (hybrid_basis.hpp), which every
// dt shares: the structure part of an operator key, what of the structure
// the reduction keeps besides its matrices (rail lines, output points, a
// beam deck's rows) and the modes asked (a count, else the cut-off).
std::string hybrid_basis_key(const std::string& structure_part, const StructureModel& structure, int modes,
                             double cutoff_hz);

}  // namespace railvsi::scheduler

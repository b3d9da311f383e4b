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
// whether the rail flexibility block is needed (multibody trains).
std::string operator_key(const std::string& structure_hash, const AnalysisOptions& analysis, bool rail_flexibility);

// The key of a modal basis and the pass built on it (modal moving forces):
// the structure hash, its rail lines (node x and element DOFs) and output
// points (name, x, DOF), which the run reads from the basis's structure,
// the modal cut-off and dt.
std::string modal_operator_key(const std::string& structure_hash, const StructureModel& structure, double cutoff_hz,
                               double dt_s);

}  // namespace railvsi::scheduler

#pragma once
// The summary JSON of a run: printed by `vsi simulate` (README "Commands",
// the summary keys); its fidelity and warnings are stored with every job.
#include <nlohmann/json.hpp>

#include "simulation/result.hpp"

namespace railvsi {

// Keys in the order of the contract. Non-finite numbers become null, and so
// do the wheel values of a train of moving forces (it has no wheels); a
// "message" follows the status when the run failed.
nlohmann::ordered_json summary_json(const Result& result, bool moving_forces);

// The "fidelity" object of the summary: the model, contact law, solver
// path, sizes and HHT parameters a run actually used.
nlohmann::ordered_json fidelity_json(const FidelityRecord& fidelity);

// The "warnings" array of the summary: [{code, message, t_s?, wheel?, factor?}].
nlohmann::ordered_json warnings_json(const std::vector<RunWarning>& warnings);

}  // namespace railvsi

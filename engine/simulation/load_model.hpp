#pragma once
// What loads the structure: the axle forces of a load model, or multibody
// vehicles coupled by wheel-rail contact. One spelling per model, the
// schema's (analysis.schema.json, fidelity.model), in scenes, records, the
// store and the price table.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace railvsi {

enum class LoadModel { kMovingForces, kInteraction };

// "moving_forces" or "interaction".
const char* load_model_name(LoadModel model);
// nullopt for a name that is none of load_model_names().
std::optional<LoadModel> parse_load_model(std::string_view name);
std::vector<std::string> load_model_names();

}  // namespace railvsi

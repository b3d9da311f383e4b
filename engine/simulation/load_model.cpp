#include "simulation/load_model.hpp"

namespace railvsi {

const char* load_model_name(LoadModel model) {
  return model == LoadModel::kMovingForces ? "moving_forces" : "interaction";
}

std::optional<LoadModel> parse_load_model(std::string_view name) {
  for (const LoadModel m : {LoadModel::kMovingForces, LoadModel::kInteraction})
    if (name == load_model_name(m)) return m;
  return std::nullopt;
}

std::vector<std::string> load_model_names() {
  return {load_model_name(LoadModel::kMovingForces), load_model_name(LoadModel::kInteraction)};
}

}  // namespace railvsi

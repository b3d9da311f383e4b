#pragma once
// The structure of a scene: the bridge-2d generator, or a model imported
// from Matrix Market files plus a JSON map (schema structure-map.schema.json).
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "io/imported_structures.hpp"
#include "model/structure_model.hpp"
#include "model/train.hpp"

namespace railvsi {

// `structure` and `outputs` are the validated /structure and /outputs values
// of a scene (outputs may be an empty object). InputError paths are absolute
// in the scene; errors in the map file name that file. The train sizes the
// default approach embankment of a generated track. An import is read
// through `imports` when given (once for the same files and content_key).
std::shared_ptr<const StructureModel> parse_structure(const nlohmann::json& structure,
                                                      const nlohmann::json& outputs,
                                                      const std::filesystem::path& base_dir,
                                                      const Train& train, ImportedStructures* imports = nullptr,
                                                      const std::string& content_key = "");

}  // namespace railvsi

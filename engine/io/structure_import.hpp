#pragma once
// An imported structure: K, M (and C) in any format make_matrix_reader reads,
// plus a JSON map (schema structure-map.schema.json) of the rail lines,
// output points and track, by equation or by the package's node and DOF
// labels. Checks on import, each an InputError naming the file and the line
// (matrix files) or JSON path (map): sizes, symmetry, non-finite entries,
// rail nodes missing from the matrices or out of order along x, a
// constrained DOF left in (a zero row of K), mass not positive definite on
// the rail DOFs. What was matched is recorded in StructureInfo::import_notes.
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "model/structure_model.hpp"

namespace railvsi {

// `structure` is the validated /structure value of a scene with "import".
std::shared_ptr<const StructureModel> import_structure(const nlohmann::json& structure, const nlohmann::json& outputs,
                                                       const std::filesystem::path& base_dir);

// Names of a list of objects must be unique (they become column names).
void check_unique_names(const nlohmann::json& list, const std::string& path);

}  // namespace railvsi

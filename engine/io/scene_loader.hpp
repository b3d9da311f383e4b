#pragma once
// Scenes from JSON (schemas/scene.schema.json): schema validation, semantic
// checks, and construction of the immutable models of one run. Every error is
// an InputError naming the file and the JSON pointer of the offending value.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/imported_structures.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

Scene load_scene(const std::filesystem::path& file);

// `doc` already read; relative file names (profiles, matrices, maps) are
// resolved from base_dir; file_for_errors names the document in errors.
// An imported structure is read through `imports` when given (see
// ImportedStructures::import for content_key).
Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& base_dir,
                  const std::string& file_for_errors, ImportedStructures* imports = nullptr,
                  const std::string& content_key = "");

// The analysis options of a validated /analysis object (paths absolute).
AnalysisOptions parse_analysis(const nlohmann::json& analysis);

}  // namespace railvsi

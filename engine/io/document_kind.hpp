#pragma once
// What kind of input document a file is, for `vsi validate`: told by the
// file name of its "$schema", else by its keys.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace railvsi {

enum class DocumentKind { kScene, kTrain, kIrregularity };

std::string_view document_kind_name(DocumentKind kind);  // "scene", "train", "irregularity"

// Throws InputError (at "/$schema" for an unknown schema, "/" when neither
// the schema nor the keys tell) naming file_for_errors.
DocumentKind detect_document_kind(const nlohmann::json& doc, const std::string& file_for_errors);

// Reads the file and runs the input checks (schema, semantics, construction
// of the models). The engine's setup checks (factorization, static
// equilibrium) are Simulation's: `vsi validate` runs them too. Throws InputError.
DocumentKind validate_document(const std::filesystem::path& file);

}  // namespace railvsi

#pragma once
// Track irregularity profiles from JSON: {"csv": "file.csv"} or inline
// {"x_m": [...], "r_m": [...]}.
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "model/irregularity.hpp"

namespace railvsi {

// `node` is a validated irregularity object; relative CSV names are resolved
// from base_dir. InputError paths are relative to the node; CSV problems are
// reported at "/csv" with the CSV file and line in the message.
std::shared_ptr<const Irregularity> parse_irregularity(const nlohmann::json& node,
                                                       const std::filesystem::path& base_dir);

// A profile document of its own (schema irregularity.schema.json), already
// read from `file`.
std::shared_ptr<const Irregularity> parse_irregularity_document(const nlohmann::json& doc,
                                                                const std::filesystem::path& file);

}  // namespace railvsi

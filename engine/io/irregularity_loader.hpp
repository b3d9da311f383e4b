#pragma once
// Track irregularity profiles from JSON (schemas/irregularity.schema.json):
// one base profile, {"csv": "file.csv"}, inline {"x_m": [...], "r_m": [...]}
// or a spectrum {"spectrum": "german-high", "seed": 7, ...}, and/or isolated
// {"defects": [...]} added to it.
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "generators/spectrum_profile.hpp"
#include "model/irregularity.hpp"

namespace railvsi {

// `node` is a validated irregularity object; relative CSV names are resolved
// from base_dir. A spectrum is sampled over `track` (widened to cover the
// defects). InputError paths are relative to the node; CSV problems are
// reported at "/csv" with the CSV file and line in the message.
std::shared_ptr<const Irregularity> parse_irregularity(const nlohmann::json& node,
                                                       const std::filesystem::path& base_dir, TrackRange track);

// Where a profile document of its own samples a spectrum: it has no track.
inline constexpr TrackRange kStandaloneProfileRange{0.0, 100.0};

// A profile document of its own (schema irregularity.schema.json), already
// read from `file`.
std::shared_ptr<const Irregularity> parse_irregularity_document(const nlohmann::json& doc,
                                                                const std::filesystem::path& file);

}  // namespace railvsi

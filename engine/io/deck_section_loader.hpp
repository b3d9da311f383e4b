#pragma once
// Deck section documents (schemas/deck-section.schema.json) for the 3D deck
// generator: the solid rectangle or a single-cell box girder.
#include <string>

#include <nlohmann/json.hpp>

#include "generators/deck_3d.hpp"

namespace railvsi {

// Validates `doc` (read from `file`) and sets the section of `options`.
// InputError names the file and the JSON path (e.g. "/web_thickness_m").
void apply_deck_section_document(const nlohmann::json& doc, const std::string& file, Deck3dOptions& options);

}  // namespace railvsi

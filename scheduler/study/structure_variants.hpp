#pragma once
// Bounds of the structure as a study dimension (EN 1991-2 6.4.6.3): the
// study's "variants": {"mass_factor": [...], "EI_factor": [...]} expands into
// every combination; each job's scene carries its own in structure.variant
// (absent for the nominal structure, so that a nominal job is the job of the
// same study without variants), which the engine applies to the deck (or the
// imported M and K). Different variants have different structures, hence
// different job ids and factorization keys.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

struct StructureVariant {
  double mass_factor = 1.0;
  double EI_factor = 1.0;
  bool nominal() const { return mass_factor == 1.0 && EI_factor == 1.0; }
  // The scene's structure.variant; null for the nominal structure.
  nlohmann::json scene_value() const;
};

// Every combination, mass factors outer, in the study's order; {nominal}
// when the study has no variants. InputError at /variants/... for repeated
// factors, or at /structure/variant when the study's structure gives one
// too, and at /variants for more combinations than max_count.
std::vector<StructureVariant> study_variants(const nlohmann::json& study, std::size_t max_count);

// How results name a variant: "nominal", or e.g. "mass x0.9" or
// "mass x1.1, EI x0.95" (the factors other than 1). `variant` is a scene's
// structure.variant (null or absent: nominal).
std::string variant_label(const nlohmann::json& variant);
std::string variant_label(const StructureVariant& variant);

}  // namespace railvsi::scheduler

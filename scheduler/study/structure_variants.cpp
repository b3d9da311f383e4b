#include "study/structure_variants.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/json_document.hpp"

namespace railvsi::scheduler {
namespace {

std::vector<double> factors(const nlohmann::json& variants, const char* key) {
  if (!variants.contains(key)) return {1.0};
  std::vector<double> list = variants.at(key).get<std::vector<double>>();
  for (std::size_t i = 0; i < list.size(); ++i)
    if (std::count(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(i), list[i]) > 0)
      throw InputError(child_path(std::string("/variants/") + key, i), fmt::format("{} is listed twice", list[i]));
  return list;
}

}  // namespace

nlohmann::json StructureVariant::scene_value() const {
  if (nominal()) return nullptr;
  return {{"mass_factor", mass_factor}, {"EI_factor", EI_factor}};
}

std::vector<StructureVariant> study_variants(const nlohmann::json& study) {
  if (!study.contains("variants")) return {StructureVariant{}};
  if (study.at("structure").contains("variant"))
    throw InputError("/structure/variant", "give the bounds of the structure in the study's variants, not both");
  const nlohmann::json& v = study.at("variants");
  std::vector<StructureVariant> out;
  for (double m : factors(v, "mass_factor"))
    for (double k : factors(v, "EI_factor")) out.push_back({m, k});
  return out;
}

std::string variant_label(const StructureVariant& v) {
  if (v.nominal()) return "nominal";
  std::string label;
  if (v.mass_factor != 1.0) label = fmt::format("mass x{:g}", v.mass_factor);
  if (v.EI_factor != 1.0) label += fmt::format("{}EI x{:g}", label.empty() ? "" : ", ", v.EI_factor);
  return label;
}

std::string variant_label(const nlohmann::json& variant) {
  if (!variant.is_object()) return "nominal";
  return variant_label(StructureVariant{variant.value("mass_factor", 1.0), variant.value("EI_factor", 1.0)});
}

}  // namespace railvsi::scheduler

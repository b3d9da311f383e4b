#include "study/structure_variants.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/json_document.hpp"

namespace railvsi::scheduler {
namespace {

std::vector<double> factors(const nlohmann::json& variants, const char* key) {
  if (!variants.contains(key)) return {1.0};
  std::vector<double> list = variants.at(key).get<std::vector<double>>();
  std::set<double> seen;  // a set: the pairwise search took minutes on 40,000 factors
  for (std::size_t i = 0; i < list.size(); ++i)
    if (!seen.insert(list[i]).second)
      throw InputError(child_path(std::string("/variants/") + key, i), fmt::format("{} is listed twice", list[i]));
  return list;
}

}  // namespace

nlohmann::json StructureVariant::scene_value() const {
  if (nominal()) return nullptr;
  return {{"mass_factor", mass_factor}, {"EI_factor", EI_factor}};
}

std::vector<StructureVariant> study_variants(const nlohmann::json& study, std::size_t max_count) {
  if (!study.contains("variants")) return {StructureVariant{}};
  if (study.contains("structure") && study.at("structure").contains("variant"))
    throw InputError("/structure/variant", "give the bounds of the structure in the study's variants, not both");
  const nlohmann::json& v = study.at("variants");
  const std::vector<double> masses = factors(v, "mass_factor"), stiffnesses = factors(v, "EI_factor");
  // Counted before the combinations are made (each is at least one job).
  const double count = static_cast<double>(masses.size()) * static_cast<double>(stiffnesses.size());
  if (count > static_cast<double>(max_count))
    throw InputError("/variants", fmt::format("gives {:.0f} variants ({} mass factors x {} EI factors), more than the "
                                              "{} jobs a study may have",
                                              count, masses.size(), stiffnesses.size(), max_count));
  std::vector<StructureVariant> out;
  for (double m : masses)
    for (double k : stiffnesses) out.push_back({m, k});
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

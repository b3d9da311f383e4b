#include "io/structure_loader.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/bridge_2d.hpp"
#include "io/json_document.hpp"
#include "io/structure_import.hpp"
#include "model/en1991_damping.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

// ---- bridge-2d

TrackOptions track_options(const json& t) {
  TrackOptions o;  // the defaults stay where the generator defines them
  const std::pair<const char*, double*> fields[] = {
      {"rail_EI_Nm2", &o.rail_EI_Nm2},
      {"rail_mass_kg_per_m", &o.rail_mass_kg_per_m},
      {"pad_k_N_per_m", &o.pad_k_N_per_m},
      {"pad_c_Ns_per_m", &o.pad_c_Ns_per_m},
      {"sleeper_spacing_m", &o.sleeper_spacing_m},
      {"sleeper_mass_kg", &o.sleeper_mass_kg},
      {"ballast_k_N_per_m", &o.ballast_k_N_per_m},
      {"ballast_c_Ns_per_m", &o.ballast_c_Ns_per_m},
      {"ballast_mass_kg", &o.ballast_mass_kg},
      {"subballast_k_N_per_m", &o.subballast_k_N_per_m},
      {"subballast_c_Ns_per_m", &o.subballast_c_Ns_per_m},
      {"approach_m", &o.approach_m},
      {"exit_m", &o.exit_m}};
  for (const auto& [key, field] : fields) *field = t.value(key, *field);
  return o;
}

Bridge2dOptions bridge_options(const json& s, const json& outputs, double min_approach_m) {
  Bridge2dOptions o;
  o.spans_m = s.at("spans_m").get<std::vector<double>>();
  o.continuous = s.value("continuous", o.continuous);
  o.deck_EI_Nm2 = s.at("deck").value("EI_Nm2", 0.0);
  o.deck_first_frequency_hz = s.at("deck").value("first_frequency_hz", 0.0);
  o.deck_mass_kg_per_m = s.at("deck").at("mass_kg_per_m").get<double>();
  if (s.contains("variant")) {  // a bound of mass and stiffness (EN 1991-2 6.4.6.3) of the deck
    const double mass_factor = s.at("variant").value("mass_factor", 1.0);
    const double EI_factor = s.at("variant").value("EI_factor", 1.0);
    o.deck_mass_kg_per_m *= mass_factor;
    o.deck_EI_Nm2 *= EI_factor;
    // EI = m (2 L^2 f1 / pi)^2: the given f1 stands for the unscaled deck.
    o.deck_first_frequency_hz *= std::sqrt(EI_factor / mass_factor);
  }
  const json& damping = s.at("damping");
  // Checked here rather than by a oneOf in the schema: the message can say what to do.
  if (damping.contains("en1991") == damping.contains("ratio"))
    throw InputError("/structure/damping", "give exactly one of ratio (the damping ratio) and en1991 (the lower "
                                           "bound of EN 1991-2 Table 6.6 for a bridge type)");
  if (damping.contains("en1991")) {
    const auto type = damping.at("en1991").at("bridge_type").get<std::string>();
    o.damping_en1991 = en1991_bridge_type_from_name(type);
    if (!o.damping_en1991)  // the schema's enum lists the names; kept in step by a test
      throw InputError("/structure/damping/en1991/bridge_type", fmt::format("unknown bridge type '{}'", type));
  } else {
    o.damping_ratio = damping.at("ratio").get<double>();
  }
  o.damping_f1_hz = damping.value("f1_hz", o.damping_f1_hz);
  o.damping_f2_hz = damping.value("f2_hz", o.damping_f2_hz);
  o.element_length_m = s.value("element_length_m", o.element_length_m);
  {  // Checked before the generator allocates: a plane model beyond this is a typo.
    double length_m = 0.0;
    for (double L : o.spans_m) length_m += L;
    const double elements = length_m / o.element_length_m;
    constexpr double kMaxDeckElements = 1.0e6;
    if (elements > kMaxDeckElements)
      throw InputError("/structure/element_length_m",
                       fmt::format("{:.3g} m of deck in elements of {:g} m makes {:.3g} elements, more than {:g}",
                                   length_m, o.element_length_m, elements, kMaxDeckElements));
  }
  if (s.contains("bearing_k_N_per_m")) o.bearing_k_N_per_m = s.at("bearing_k_N_per_m").get<double>();
  if (s.contains("track") && !s.at("track").is_null()) {
    o.track = track_options(s.at("track"));
    if (!s.at("track").contains("approach_m")) o.track->approach_m = std::max(o.track->approach_m, min_approach_m);
  }
  if (outputs.contains("points")) {
    check_unique_names(outputs.at("points"), "/outputs/points");
    for (const json& p : outputs.at("points"))
      o.output_points.emplace_back(p.at("name").get<std::string>(), p.at("x_m").get<double>());
  }
  return o;
}

}  // namespace

std::shared_ptr<const StructureModel> parse_structure(const json& structure, const json& outputs,
                                                      const std::filesystem::path& base_dir,
                                                      const Train& train, ImportedStructures* imports,
                                                      const std::string& content_key) {
  if (structure.contains("import"))
    return imports ? imports->import(structure, outputs, base_dir, content_key)
                   : import_structure(structure, outputs, base_dir);
  // A multibody train starts wholly on the track (static equilibrium, no
  // entry transient) when the approach is not given explicitly.
  const double min_approach_m = train.is_moving_forces() ? 0.0 : train.length_m() + 10.0;
  return make_bridge_2d(bridge_options(structure, outputs, min_approach_m));
}

}  // namespace railvsi

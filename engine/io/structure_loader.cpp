#include "io/structure_loader.hpp"

#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/bridge_2d.hpp"
#include "io/json_document.hpp"
#include "io/matrix_market.hpp"
#include "io/schema_validator.hpp"
#include "model/en1991_damping.hpp"
#include "model/rayleigh.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

// Names of a list of objects must be unique (they become column names).
void check_unique_names(const json& list, const std::string& path) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto name = list[i].at("name").get<std::string>();
    if (const auto [it, fresh] = seen.emplace(name, i); !fresh)
      throw InputError(child_path(child_path(path, i), "name"),
                       fmt::format("duplicate name '{}' (already used at {})", name, child_path(path, it->second)));
  }
}

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

// ---- import: the map file

struct StructureMap {
  std::vector<RailLine> rails;
  std::vector<OutputPoint> outputs;
  StructureInfo info;
};

RailLine map_rail_line(const json& line, const std::string& path) {
  const auto x_m = line.at("x_m").get<std::vector<double>>();
  const auto dof_v = line.at("dof_v").get<std::vector<int>>();
  const auto dof_rot = line.at("dof_rot").get<std::vector<int>>();
  for (const char* key : {"dof_v", "dof_rot"})
    if (line.at(key).size() != x_m.size())
      throw InputError(child_path(path, key),
                       fmt::format("has {} entries but x_m has {}: one per node", line.at(key).size(), x_m.size()));
  return RailLine::from_nodes(line.at("name").get<std::string>(), x_m, dof_v, dof_rot);
}

StructureMap parse_structure_map(const json& doc) {
  StructureMap map;
  check_unique_names(doc.at("rail_lines"), "/rail_lines");
  for (std::size_t r = 0; r < doc.at("rail_lines").size(); ++r)
    map.rails.push_back(map_rail_line(doc.at("rail_lines")[r], child_path("/rail_lines", r)));
  if (doc.contains("output_points")) {
    check_unique_names(doc.at("output_points"), "/output_points");
    for (const json& p : doc.at("output_points"))
      map.outputs.push_back({p.at("name").get<std::string>(), p.at("x_m").get<double>(), p.at("dof").get<int>()});
  }
  map.info.source = "import";
  // Rail nodes increase strictly (checked by StructureModel); until then
  // take the ends as given.
  map.info.bridge_start_m = doc.value("bridge_start_m", map.rails.front().x_m.front());
  map.info.bridge_end_m = doc.value("bridge_end_m", map.rails.front().x_m.back());
  if (!(map.info.bridge_end_m > map.info.bridge_start_m))
    throw InputError("/bridge_end_m", fmt::format("must be greater than bridge_start_m ({})", map.info.bridge_start_m));
  return map;
}

// ---- import: matrices and damping

struct ImportedMatrices {
  SparseMatrix K, M, C;
  std::map<std::string, std::string> files;  // "K" -> file name, for messages
};

ImportedMatrices read_matrices(const json& files, const std::filesystem::path& base_dir) {
  ImportedMatrices m;
  auto read = [&](const char* key) {
    const auto file = resolve_relative(base_dir, files.at(key).get<std::string>());
    m.files[key] = file.string();
    return read_matrix_market(file, child_path("/structure/import", key));
  };
  m.K = read("K");
  m.M = read("M");
  if (files.contains("C")) m.C = read("C");
  if (m.M.rows() != m.K.rows())
    throw InputError("/structure/import/M", fmt::format("{}: M is {} x {} but K is {} x {}; sizes must agree",
                                                        m.files["M"], m.M.rows(), m.M.cols(), m.K.rows(), m.K.cols()));
  return m;
}

// C = a0 M + a1 K with the ratio matched at f1 and f2.
SparseMatrix rayleigh_damping(const ImportedMatrices& m, const json& damping) {
  const double f1 = damping.at("f1_hz").get<double>(), f2 = damping.at("f2_hz").get<double>();
  if (!(f2 > f1)) throw InputError("/structure/damping/f2_hz", "must be greater than f1_hz");
  const RayleighCoefficients r = rayleigh_coefficients(damping.at("ratio").get<double>(), f1, f2);
  return SparseMatrix(r.a0_per_s * m.M + r.a1_s * m.K);
}

// StructureModel reports "/structure/...": rail lines and output points are
// in the map file, matrices in the scene's import object.
InputError place_model_error(const InputError& e, const ImportedMatrices& m, const std::string& map_file) {
  const std::string& path = e.json_path();
  const std::string rest = path.substr(std::string("/structure").size());
  if (rest.starts_with("/rail_lines") || rest.starts_with("/output_points")) return InputError(rest, e.what(), map_file);
  for (const auto& [key, file] : m.files)
    if (rest == "/" + key) return InputError(child_path("/structure/import", key), fmt::format("{}: {}", file, e.what()));
  return InputError("/structure/import", e.what());
}

std::shared_ptr<const StructureModel> import_structure(const json& s, const json& outputs,
                                                       const std::filesystem::path& base_dir) {
  if (outputs.contains("points"))
    throw InputError("/outputs/points", "an imported structure lists its output points in its map file");
  const json& files = s.at("import");
  if (files.contains("C") && s.contains("damping"))
    throw InputError("/structure/damping", "give either import.C or damping, not both");
  ImportedMatrices m = read_matrices(files, base_dir);
  if (s.contains("damping")) m.C = rayleigh_damping(m, s.at("damping"));
  const auto map_file = resolve_relative(base_dir, files.at("map").get<std::string>()).string();
  const json map_doc = read_json_file(map_file);
  StructureMap map = parse_validated(map_doc, "structure-map.schema.json", map_file,
                                     [&] { return parse_structure_map(map_doc); });
  map.info.deck_dofs = static_cast<int>(m.K.rows());  // the whole model counts as structure
  if (s.contains("damping")) {
    map.info.damping_ratio = s.at("damping").at("ratio").get<double>();
    map.info.damping_source = "given (Rayleigh on the whole imported model)";
  } else {
    map.info.damping_source = files.contains("C") ? "imported C matrix" : "none";
    if (!files.contains("C")) map.info.damping_ratio = 0.0;
  }
  try {
    return std::make_shared<const StructureModel>(m.K, m.M, m.C, std::move(map.rails), std::move(map.outputs),
                                                  std::move(map.info));
  } catch (const InputError& e) {
    throw place_model_error(e, m, map_file);
  }
}

}  // namespace

std::shared_ptr<const StructureModel> parse_structure(const json& structure, const json& outputs,
                                                      const std::filesystem::path& base_dir,
                                                      const Train& train) {
  if (structure.contains("import")) return import_structure(structure, outputs, base_dir);
  // A multibody train starts wholly on the track (static equilibrium, no
  // entry transient) when the approach is not given explicitly.
  const double min_approach_m = train.is_moving_forces() ? 0.0 : train.length_m() + 10.0;
  return make_bridge_2d(bridge_options(structure, outputs, min_approach_m));
}

}  // namespace railvsi

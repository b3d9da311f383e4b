#include "io/train_loader.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/input_error.hpp"
#include "generators/hslm.hpp"
#include "generators/vehicle_2d.hpp"
#include "io/json_document.hpp"
#include "io/schema_validator.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

std::optional<double> optional_number(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? std::nullopt : std::optional<double>(it->get<double>());
}

SpringDamper spring_damper(const json& s) {
  return {s.at("k_N_per_m").get<double>(), s.at("c_Ns_per_m").get<double>()};
}

Car2dOptions car_2d_options(const json& car) {
  Car2dOptions o;
  o.name = car.at("name").get<std::string>();
  o.body_mass_kg = car.at("car_body").at("mass_kg").get<double>();
  o.body_pitch_inertia_kgm2 = car.at("car_body").at("pitch_inertia_kgm2").get<double>();
  o.bogie_mass_kg = car.at("bogie").at("mass_kg").get<double>();
  o.bogie_pitch_inertia_kgm2 = car.at("bogie").at("pitch_inertia_kgm2").get<double>();
  o.wheelset_mass_kg = car.at("wheelset").at("mass_kg").get<double>();
  o.wheel_radius_m = car.at("wheelset").value("radius_m", o.wheel_radius_m);
  o.bogie_spacing_m = car.at("bogie_spacing_m").get<double>();
  o.axle_spacing_m = car.at("axle_spacing_m").get<double>();
  o.primary = spring_damper(car.at("primary"));
  o.secondary = spring_damper(car.at("secondary"));
  return o;
}

Articulated2dOptions articulated_2d_options(const json& set) {
  return {car_2d_options(set), set.at("bodies").get<int>()};
}

std::shared_ptr<const VehicleModel> template_vehicle(const json& v) {
  if (v.at("template").get<std::string>() == "articulated-2d") return make_articulated_2d(articulated_2d_options(v));
  return make_car_2d(car_2d_options(v));
}

// A square matrix given as a list of rows; `path` is its JSON pointer.
DenseMatrix dense_matrix(const json& rows, const std::string& path) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  DenseMatrix A(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const json& row = rows[static_cast<std::size_t>(i)];
    if (static_cast<Eigen::Index>(row.size()) != n)
      throw InputError(child_path(path, static_cast<std::size_t>(i)),
                       fmt::format("row has {} values; the matrix has {} rows and must be square", row.size(), n));
    for (Eigen::Index j = 0; j < n; ++j) A(i, j) = row[static_cast<std::size_t>(j)].get<double>();
  }
  return A;
}

std::shared_ptr<const VehicleModel> imported_vehicle(const json& v) {
  const json& m = v.at("matrices");
  DenseMatrix C = m.contains("C") ? dense_matrix(m.at("C"), "/matrices/C") : DenseMatrix();
  const auto flags = v.at("vertical_dofs").get<std::vector<double>>();
  const Vector gravity_dofs = Eigen::Map<const Vector>(flags.data(), static_cast<Eigen::Index>(flags.size()));
  std::vector<Wheel> wheels;
  for (const json& w : v.at("wheels")) {
    Wheel wheel;
    wheel.dof = w.at("dof").get<int>();
    wheel.offset_m = w.at("offset_m").get<double>();
    wheel.radius_m = w.value("radius_m", wheel.radius_m);
    wheels.push_back(wheel);
  }
  std::optional<std::vector<int>> body_dofs;
  if (v.contains("body_dofs")) body_dofs = v.at("body_dofs").get<std::vector<int>>();
  return std::make_shared<const VehicleModel>(
      v.at("name").get<std::string>(), dense_matrix(m.at("K"), "/matrices/K"), dense_matrix(m.at("M"), "/matrices/M"),
      std::move(C), gravity_dofs, std::move(wheels), std::move(body_dofs));
}

// Identical car definitions (placement aside) share one model.
class VehicleCatalog {
 public:
  std::shared_ptr<const VehicleModel> model_of(const json& car, const std::string& path) {
    json definition = car;
    for (const char* placement : {"offset_m", "count", "length_m", "source"}) definition.erase(placement);
    auto& model = models_[definition.dump()];
    if (!model)
      model = with_path_prefix(path, [&] {
        return car.contains("template") ? template_vehicle(car) : imported_vehicle(car);
      });
    return model;
  }

 private:
  std::map<std::string, std::shared_ptr<const VehicleModel>> models_;
};

// One entry of "vehicles": its model and where its copies stand.
struct PlacedCar {
  std::string path;
  std::shared_ptr<const VehicleModel> model;
  std::vector<double> offsets_m;  // first axle of each copy
};

// Cars front to back; a car without offset_m follows the previous one.
std::vector<PlacedCar> place_cars(const json& cars) {
  VehicleCatalog catalog;
  std::vector<PlacedCar> placed;
  std::optional<double> next_offset_m = 0.0;  // where a car without offset_m goes
  for (std::size_t i = 0; i < cars.size(); ++i) {
    const json& car = cars[i];
    PlacedCar p{child_path("/vehicles", i), nullptr, {}};
    p.model = catalog.model_of(car, p.path);
    const std::optional<double> length_m = optional_number(car, "length_m");
    const int count = car.value("count", 1);
    if (count > 1 && !length_m)
      throw InputError(p.path + "/length_m", "needed to repeat the car (count > 1)");
    const std::optional<double> given_offset_m = optional_number(car, "offset_m");
    if (!given_offset_m && !next_offset_m)
      throw InputError(p.path + "/offset_m",
                       "needed: the previous car has no length_m to place this one behind it");
    const double offset_m = given_offset_m ? *given_offset_m : *next_offset_m;
    for (int k = 0; k < count; ++k) p.offsets_m.push_back(offset_m + k * length_m.value_or(0.0));
    next_offset_m = length_m ? std::optional<double>(offset_m + count * *length_m) : std::nullopt;
    placed.push_back(std::move(p));
  }
  return placed;
}

std::vector<TrainVehicle> as_vehicles(const std::vector<PlacedCar>& cars) {
  std::vector<TrainVehicle> vehicles;
  for (const PlacedCar& car : cars)
    for (double offset_m : car.offsets_m) vehicles.push_back({car.model, offset_m});
  return vehicles;
}

// Every wheel becomes its static load on a rigid, level track.
std::vector<MovingForce> as_moving_forces(const std::vector<PlacedCar>& cars) {
  std::vector<MovingForce> forces;
  for (const PlacedCar& car : cars) {
    const Vector loads_N = with_path_prefix(car.path, [&] { return static_wheel_loads_on_rigid_track(*car.model); });
    const auto& wheels = car.model->wheels();
    for (double offset_m : car.offsets_m)
      for (std::size_t w = 0; w < wheels.size(); ++w)
        forces.push_back({offset_m + wheels[w].offset_m, loads_N[static_cast<Eigen::Index>(w)]});
  }
  std::stable_sort(forces.begin(), forces.end(),
                   [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; });
  return forces;
}

std::vector<MovingForce> moving_forces(const json& list) {
  std::vector<MovingForce> forces;
  for (const json& f : list) forces.push_back({f.at("offset_m").get<double>(), f.at("load_N").get<double>()});
  return forces;
}

Train hslm_a_train(const json& h, std::string name) {
  HslmAOptions o;
  o.intermediate_coaches = h.at("intermediate_coaches").get<int>();
  o.coach_length_m = h.at("coach_length_m").get<double>();
  o.bogie_axle_spacing_m = h.at("bogie_axle_spacing_m").get<double>();
  o.axle_load_N = h.at("axle_load_N").get<double>();
  return with_path_prefix("/hslm_a", [&] { return make_hslm_a(o, std::move(name)); });
}

Train hslm_b_train(const json& h, std::string name) {
  HslmBOptions o;
  o.span_m = h.value("span_m", 0.0);
  if (!h.contains("point_forces") || !h.contains("spacing_m"))
    throw InputError("/hslm_b",
                     "give point_forces (N) and spacing_m (d) read from EN 1991-2 Figure 6.14 (Annex E) for the span: "
                     "railvsi does not derive them from span_m, the figure's values are not built in (not confirmed "
                     "against the standard's text)");
  o.point_forces = h.at("point_forces").get<int>();
  o.spacing_m = h.at("spacing_m").get<double>();
  o.axle_load_N = h.value("axle_load_N", o.axle_load_N);
  return with_path_prefix("/hslm_b", [&] { return make_hslm_b(o, std::move(name)); });
}

}  // namespace

std::filesystem::path train_library_dir() {
  const char* library = std::getenv("RAILVSI_LIBRARY");
  if (library != nullptr && *library != '\0') return std::filesystem::path(library) / "trains";
  // An installed binary: <prefix>/bin/vsi finds <prefix>/share/railvsi/trains.
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = (exe.parent_path() / RAILVSI_DATA_FROM_BINARY / "trains").lexically_normal();
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  // The build tree: the library of the source tree.
  return std::filesystem::path(RAILVSI_SOURCE_DIR "/jobs") / "trains";
}

std::vector<std::string> json_file_names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool is_plain_file_name(const std::string& name) {
  return !name.empty() && name.find_first_of(std::string_view("/\\\0", 3)) == std::string::npos && name != "." &&
         name != "..";
}

std::vector<std::string> library_train_names() { return json_file_names(train_library_dir()); }

namespace {

// The document of a library train and its file.
std::pair<json, std::filesystem::path> library_document(const std::string& name) {
  // A name is never a path: one file name of the library folder (no
  // separator, not "." or ".."), opened there. The folder is listed only for
  // the message (a sweep loads a train per scene: listing it each time cost
  // more than reading the file).
  const std::filesystem::path dir = train_library_dir();
  std::filesystem::path file = dir / (name + ".json");
  std::error_code ec;
  if (!is_plain_file_name(name) || !std::filesystem::is_regular_file(file, ec)) {
    const auto names = library_train_names();
    throw InputError("", fmt::format("unknown train '{}'; the library {} has: {}", name, dir.string(),
                                     names.empty() ? std::string("no trains") : fmt::format("{}", fmt::join(names, ", "))));
  }
  return {read_json_file(file), std::move(file)};
}

}  // namespace

Train load_library_train(const std::string& name) {
  const auto [doc, file] = library_document(name);
  return parse_train_document(doc, file);
}

Train parse_train_reference(const json& train) {
  if (train.is_string()) return load_library_train(train.get<std::string>());
  if (!train.contains("library")) return parse_train(train);
  const auto name = train.at("library").get<std::string>();
  auto [doc, file] = with_path_prefix("/library", [&] { return library_document(name); });
  if (train.contains("as")) {
    const auto as = train.at("as").get<std::string>();
    if (doc.is_object() && doc.contains("vehicles")) {
      doc["as"] = as;
    } else if (as == "multibody") {
      throw InputError("/as", fmt::format("the library train '{}' is moving forces: it has no vehicles", name));
    }
  }
  return parse_train_document(doc, file);
}

Train parse_train(const json& train) {
  Train t;
  t.name = train.at("name").get<std::string>();
  const char* given = nullptr;
  for (const char* form : {"moving_forces", "hslm_a", "hslm_b", "vehicles"}) {
    if (!train.contains(form)) continue;
    if (given != nullptr)
      throw InputError(std::string("/") + form, fmt::format("give one of moving_forces, hslm_a, hslm_b and vehicles, "
                                                            "not both {} and {}",
                                                            given, form));
    given = form;
  }
  if (!train.contains("vehicles")) {
    if (train.contains("as"))
      throw InputError("/as", fmt::format("applies to vehicles only; {} are moving forces already", given));
    if (train.contains("hslm_a")) return hslm_a_train(train.at("hslm_a"), t.name);
    if (train.contains("hslm_b")) return hslm_b_train(train.at("hslm_b"), t.name);
    t.moving_forces = moving_forces(train.at("moving_forces"));
    return t;
  }
  const std::vector<PlacedCar> cars = place_cars(train.at("vehicles"));
  if (train.value("as", "multibody") == "moving_forces") {
    t.moving_forces = as_moving_forces(cars);
  } else {
    t.vehicles = as_vehicles(cars);
  }
  return t;
}

Train parse_train_document(const json& doc, const std::filesystem::path& file) {
  return parse_validated(doc, "train.schema.json", file.string(), [&] { return parse_train(doc); });
}

}  // namespace railvsi

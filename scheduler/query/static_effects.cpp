#include "query/static_effects.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "analysis/static_influence.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi::scheduler {

std::optional<double> DynamicIncrement::phi_dyn() const {
  if (!dynamic_value || !(static_value > 0.0)) return std::nullopt;
  return *dynamic_value / static_value - 1.0;
}

std::vector<std::pair<double, double>> DynamicIncrement::phi_dyn_by_speed() const {
  std::vector<std::pair<double, double>> out;
  if (!(static_value > 0.0)) return out;
  for (const auto& [speed_kmh, dynamic] : dynamic_by_speed) out.emplace_back(speed_kmh, dynamic / static_value - 1.0);
  return out;
}

std::vector<DynamicIncrement> dynamic_increments(Database& db, const std::vector<JobResult>& jobs,
                                                 std::vector<std::string>& notes, const KnownStatics* known) {
  std::vector<DynamicIncrement> out;
  std::vector<std::string> trains;
  std::map<std::string, std::vector<const JobResult*>> by_train;
  for (const JobResult& j : jobs) {
    if (!by_train.count(j.train)) trains.push_back(j.train);
    by_train[j.train].push_back(&j);
  }
  if (trains.empty()) return out;
  // Every job of a study shares its structure: one influence pass.
  std::optional<Scene> first;
  std::optional<StaticInfluence> own;
  if (!known || !known->influence) {
    first.emplace(load_job_scene(db, by_train[trains.front()].front()->id));
    own.emplace(*first->structure, first->analysis.contact.rail_lines);
  }
  const StaticInfluence& influence = own ? *own : *known->influence;
  const StructureModel& structure = influence.structure();
  if (!influence.section_forms().available())
    notes.push_back("section forces: " + influence.section_forms().unavailable);
  for (const std::string& t : trains) {
    const auto it = known ? known->trains.find(t) : std::map<std::string, TrainStatics>::const_iterator{};
    const TrainStatics* given = known && it != known->trains.end() ? &it->second : nullptr;
    const std::vector<MovingForce> axles =
        given ? std::vector<MovingForce>{} : axle_loads(load_job_scene(db, by_train[t].front()->id).train);
    const auto add = [&](const char* quantity, const std::string& location, double static_value) {
      DynamicIncrement d{t, quantity, location, static_value, std::nullopt, 0.0, 0, {}};
      std::map<double, double> by_speed;
      for (const JobResult* j : by_train[t]) {
        std::optional<double> v;
        const auto q = j->envelopes.find(quantity);
        if (q != j->envelopes.end()) {
          const auto l = q->second.find(location);
          if (l != q->second.end()) v = l->second;
        }
        if (!v) {
          ++d.jobs_without_value;
          continue;
        }
        if (!d.dynamic_value || *v > *d.dynamic_value) d.dynamic_value = v, d.governing_speed_kmh = j->speed_kmh;
        const auto [it, fresh] = by_speed.try_emplace(j->speed_kmh, *v);
        if (!fresh) it->second = std::max(it->second, *v);
      }
      d.dynamic_by_speed.assign(by_speed.begin(), by_speed.end());
      out.push_back(std::move(d));
    };
    const auto& points = structure.outputs();
    for (std::size_t k = 0; k < points.size(); ++k)
      add("deck_displacement_m", points[k].name,
          given ? given->max_deflection_m.at(k) : influence.train_envelope(static_cast<int>(k), axles).max_deflection_m);
    const StaticSectionEnvelope e = given ? given->sections : influence.section_envelope(axles);
    if (!e.unavailable.empty()) continue;
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (e.max_abs_bending_moment_Nm[k]) add("bending_moment_Nm", points[k].name, *e.max_abs_bending_moment_Nm[k]);
      if (e.max_abs_shear_force_N[k]) add("shear_force_N", points[k].name, *e.max_abs_shear_force_N[k]);
    }
    const auto& supports = influence.section_forms().supports;
    for (std::size_t i = 0; i < supports.size(); ++i) {
      add("support_reaction_N", supports[i].name, e.max_reaction_N[i]);
      add("support_rotation_rad", supports[i].name, e.max_abs_rotation_rad[i]);
    }
  }
  return out;
}

nlohmann::ordered_json dynamic_increments_json(const std::vector<DynamicIncrement>& increments,
                                               const std::vector<std::string>& notes) {
  using nlohmann::ordered_json;
  const auto number = [](std::optional<double> v) {
    return v && std::isfinite(*v) ? ordered_json(*v) : ordered_json(nullptr);
  };
  ordered_json list = ordered_json::array();
  for (const DynamicIncrement& d : increments)
    list.push_back({{"train", d.train},
                    {"quantity", d.quantity},
                    {"location", d.location},
                    {"static", number(d.static_value)},
                    {"dynamic", number(d.dynamic_value)},
                    {"governing_speed_kmh", d.dynamic_value ? ordered_json(d.governing_speed_kmh) : ordered_json(nullptr)},
                    {"jobs_without_value", d.jobs_without_value},
                    {"phi_dyn_prime", number(d.phi_dyn())}});
  return {{"clause", "EN 1991-2 6.4.6.5: phi'dyn = max dynamic / max static - 1 per load effect"},
          {"static", "quasi-static envelope of the same train by static influence lines, computed on demand"},
          {"notes", notes},
          {"effects", list}};
}

}  // namespace railvsi::scheduler

#pragma once
// One car-2d coach (ICE3-like values) as a scene's vehicle JSON, for the
// tests of every module that run a multibody train.
#include <nlohmann/json.hpp>

namespace railvsi::testing {

inline nlohmann::json coach_json(double primary_k_N_per_m) {
  return {{"template", "car-2d"},
          {"name", "coach"},
          {"car_body", {{"mass_kg", 40000}, {"pitch_inertia_kgm2", 1.9e6}}},
          {"bogie", {{"mass_kg", 3000}, {"pitch_inertia_kgm2", 1700}}},
          {"wheelset", {{"mass_kg", 1800}, {"radius_m", 0.46}}},
          {"bogie_spacing_m", 17.5},
          {"axle_spacing_m", 2.5},
          {"primary", {{"k_N_per_m", primary_k_N_per_m}, {"c_Ns_per_m", 2.0e4}}},
          {"secondary", {{"k_N_per_m", 7.0e5}, {"c_Ns_per_m", 4.0e4}}},
          {"length_m", 25.0}};
}

}  // namespace railvsi::testing

#pragma once
// The studies the tests and the load bench of vsi serve submit.
#include <string>

#include <nlohmann/json.hpp>

namespace railvsi::test {

// Two HSLM trains over a 25 m span at `speeds` speeds from 200 km/h by
// 5 km/h: quick jobs (milliseconds each; the light deck fails the
// ballasted-track limit at resonance, so the verdict is FAIL).
inline nlohmann::json hslm_study(const std::string& name, int speeds = 5) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "structure": {
      "generator": "bridge-2d", "spans_m": [25], "continuous": false,
      "deck": {"EI_Nm2": 7.694e10, "mass_kg_per_m": 15000},
      "damping": {"ratio": 0.01}, "track": null
    },
    "trains": ["HSLM-A1", "HSLM-A2"],
    "analysis": {"hht_alpha": -0.05},
    "outputs": {"points": [{"name": "quarter", "x_m": 6.25}, {"name": "midspan", "x_m": 12.5}]},
    "checks": {"deck_acceleration_limit_mps2": 3.5}
  })");
  doc["name"] = name;
  nlohmann::json list = nlohmann::json::array();
  for (int i = 0; i < speeds; ++i) list.push_back(200 + 5 * i);
  doc["speeds_kmh"] = list;
  return doc;
}

// The ICE3 as a multibody train with Hertz contact on the same span: about
// a second a job, so that a server can be stopped in the middle of a study.
inline nlohmann::json multibody_study(const std::string& name, int speeds) {
  nlohmann::json doc = hslm_study(name, speeds);
  doc["trains"] = nlohmann::json::array({"ICE3"});
  doc["analysis"] = {{"hht_alpha", -0.05}, {"contact", {{"law", "hertz"}}}};
  return doc;
}

}  // namespace railvsi::test

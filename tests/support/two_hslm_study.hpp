#pragma once
// Two HSLM trains over the 25 m span of the README example (light deck: its
// resonances exceed the ballasted limit, so the verdict is FAIL), midspan
// and quarter points; the caller adds the speeds. Quick jobs (milliseconds
// each) for the CLI, service and report tests.
#include <string>

#include <nlohmann/json.hpp>

namespace railvsi::testing {

inline nlohmann::json two_hslm_trains_without_speeds(const std::string& name) {
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
  return doc;
}

}  // namespace railvsi::testing

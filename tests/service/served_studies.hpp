#pragma once
// The studies the tests and the load bench of vsi serve submit.
#include <string>

#include <nlohmann/json.hpp>

#include "../support/two_hslm_study.hpp"

namespace railvsi::test {

// Two HSLM trains over a 25 m span at `speeds` speeds from 200 km/h by
// 5 km/h: quick jobs (milliseconds each; the light deck fails the
// ballasted-track limit at resonance, so the verdict is FAIL).
inline nlohmann::json hslm_study(const std::string& name, int speeds = 5) {
  nlohmann::json doc = railvsi::testing::two_hslm_trains_without_speeds(name);
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

// vsi simulate --verify: the scene run again at dt/2 and each key quantity's
// relative change reported, with a dt_self_check warning for each one that
// moves more than accuracy.tolerance. The changes are checked against two
// plain vsi simulate runs at dt and dt/2 (the reference: the same binary's
// ordinary path, not the self-check's comparison).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "vsi_test_support.hpp"
#include "../support/coach_json.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// One car-2d coach (ICE3-like) at 300 km/h over a 15 m simply supported
// span on ballasted track, a cosine dip at midspan, nonlinear unilateral Hertz.
json coach_over_a_dip(double dt_s, double depth_m, double length_m) {
  const json car = railvsi::testing::coach_json(2.4e6);
  return {{"structure",
           {{"generator", "bridge-2d"},
            {"spans_m", {15}},
            {"continuous", false},
            {"deck", {{"EI_Nm2", 2.0e10}, {"mass_kg_per_m", 12000}}},
            {"damping", {{"ratio", 0.02}}},
            {"track", json::object()}}},
          {"train", {{"name", "one coach"}, {"vehicles", {car}}}},
          {"speed_kmh", 300},
          {"irregularity",
           {{"defects", {{{"type", "dip"}, {"x_m", 7.0}, {"length_m", length_m}, {"depth_m", depth_m}}}}}},
          {"analysis", {{"dt_s", dt_s}, {"hht_alpha", -0.05}, {"contact", {{"law", "hertz"}, {"unilateral", true}}}}},
          {"outputs", {{"points", {{{"name", "mid"}, {"x_m", 7.5}}}}}}};
}

class SimulateVerify : public VsiCliTest {
 protected:
  json simulate(const json& scene, const std::string& name, const std::string& flags = "") const {
    const VsiRun r = vsi("simulate '" + write_json(name + ".json", scene).string() + "' " + flags);
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    return r.exit_code == 0 ? json::parse(r.out) : json::object();
  }
  static const json& row(const json& check, const std::string& quantity) {
    for (const json& r : check.at("quantities"))
      if (r.at("quantity") == quantity) return r;
    throw std::runtime_error("no row " + quantity);
  }
  static int self_check_warnings(const json& summary, const std::string& quantity) {
    int n = 0;
    for (const json& w : summary.at("run").at("warnings"))
      if (w.at("code") == "dt_self_check" && w.at("message").get<std::string>().find(quantity) != std::string::npos) ++n;
    return n;
  }
};

// 10 mm deep over 0.5 m: the wheels lift and land; at dt = 1 ms (the
// policy asks 0.04 ms) the filtered deck acceleration moves -4.76 % and the
// contact-loss time -4.76 % at dt/2 (measured 2026-11-27).
TEST_F(SimulateVerify, ACoarseStepOverADipIsFlaggedWithTheChangeOfPlainRunsAtDtAndHalfDt) {
  const json coarse = coach_over_a_dip(1e-3, 0.01, 0.5);
  const json verified = simulate(coarse, "coarse", "--verify");
  ASSERT_TRUE(verified.contains("dt_self_check")) << verified.dump();
  const json& check = verified.at("dt_self_check");
  EXPECT_EQ(check.at("dt_s").get<double>(), 1e-3);
  EXPECT_EQ(check.at("half_dt_s").get<double>(), 5e-4);
  EXPECT_EQ(check.at("tolerance").get<double>(), 0.01);
  EXPECT_FALSE(check.at("converged").get<bool>());

  json half = coarse;
  half["analysis"]["dt_s"] = 5e-4;
  const json at_dt = simulate(coarse, "at-dt"), at_half = simulate(half, "at-half");
  ASSERT_FALSE(at_dt.empty());
  ASSERT_FALSE(at_half.empty());
  // A plain run carries no self-check.
  EXPECT_FALSE(at_dt.contains("dt_self_check"));
  EXPECT_EQ(self_check_warnings(at_dt, ""), 0);
  const std::pair<const char*, json::json_pointer> pairs[] = {
      {"deck_acceleration_mps2", json::json_pointer("/deck/max_abs_acceleration_filtered_mps2")},
      {"deck_displacement_m", json::json_pointer("/deck/max_abs_displacement_m")},
      {"contact_loss_s", json::json_pointer("/wheels/contact_loss_s")}};
  for (const auto& [quantity, pointer] : pairs) {
    const double v = at_dt.at(pointer).get<double>(), v_half = at_half.at(pointer).get<double>();
    const json& r = row(check, quantity);
    EXPECT_EQ(r.at("value").get<double>(), v) << quantity;
    EXPECT_EQ(r.at("half_dt_value").get<double>(), v_half) << quantity;
    // The same runs (deterministic): equal but for the rounding of the division.
    EXPECT_DOUBLE_EQ(r.at("relative_change").get<double>(), (v - v_half) / v_half) << quantity;
    const bool above = std::abs((v - v_half) / v_half) > 0.01;
    EXPECT_EQ(r.at("above_tolerance").get<bool>(), above) << quantity;
    EXPECT_EQ(self_check_warnings(verified, std::string(quantity) + " changes"), above ? 1 : 0) << quantity;
  }
  // Measured -4.76 % and -4.76 % (displacement -0.90 %, under the tolerance).
  EXPECT_TRUE(row(check, "deck_acceleration_mps2").at("above_tolerance").get<bool>());
  EXPECT_TRUE(row(check, "contact_loss_s").at("above_tolerance").get<bool>());
  EXPECT_FALSE(row(check, "deck_displacement_m").at("above_tolerance").get<bool>());
  // A larger tolerance lets the same change pass.
  json lenient = coarse;
  lenient["accuracy"] = {{"tolerance", 0.3}};
  const json relaxed = simulate(lenient, "lenient", "--verify");
  ASSERT_FALSE(relaxed.empty());
  EXPECT_TRUE(relaxed.at("dt_self_check").at("converged").get<bool>()) << relaxed.at("dt_self_check").dump();
  EXPECT_EQ(self_check_warnings(relaxed, ""), 0);
}

// 1 mm deep over 2 m at dt = 0.25 ms: every key quantity within 1 % of
// dt/2 (largest change: minimum contact force +0.61 %, measured
// 2026-11-27): converged, no self-check warning.
TEST_F(SimulateVerify, AConvergedStepCarriesNoWarning) {
  const json verified = simulate(coach_over_a_dip(2.5e-4, 0.001, 2.0), "converged", "--verify");
  ASSERT_TRUE(verified.contains("dt_self_check")) << verified.dump();
  const json& check = verified.at("dt_self_check");
  EXPECT_TRUE(check.at("converged").get<bool>()) << check.dump();
  EXPECT_EQ(self_check_warnings(verified, ""), 0);
  // Every key quantity of an interaction run is there with a change (none
  // missing: a missing value would be flagged, not passed).
  EXPECT_EQ(check.at("quantities").size(), 7u);
  for (const json& r : check.at("quantities")) {
    ASSERT_TRUE(r.at("relative_change").is_number()) << r.dump();
    EXPECT_LE(std::abs(r.at("relative_change").get<double>()), 0.01) << r.dump();
    EXPECT_FALSE(r.at("above_tolerance").get<bool>()) << r.dump();
  }
}

}  // namespace
}  // namespace railvsi::test

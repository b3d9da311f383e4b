// vsi query --format json: the dynamic increment phi'dyn of every load
// effect against the static envelope of the same train, computed from the
// store alone; static values against the classical closed forms.
#include <gtest/gtest.h>

#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class DynamicIncrement : public ServiceTest {};

const json* find_effect(const json& effects, const std::string& train, const std::string& quantity,
                        const std::string& location) {
  for (const json& e : effects)
    if (e.at("train") == train && e.at("quantity") == quantity && e.at("location") == location) return &e;
  return nullptr;
}

TEST_F(DynamicIncrement, QueryJsonGivesStaticDynamicAndPhiPerLoadEffect) {
  json doc = tiny_study();  // 10 m simply supported span, points at 2.5 m and 5 m
  doc["speeds_kmh"] = json::array({100, 200});
  const auto study = write_json("s.json", doc);
  const std::string db = (dir_ / "d.sqlite").string();
  const VsiResult submitted = vsi({"submit", study.string(), "--db", db});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  const std::string id = submitted.out.substr(6, 64);
  const VsiResult worked = vsi({"work", "--db", db, "--threads", "2"});
  ASSERT_EQ(worked.exit_code, 0) << worked.err;
  const VsiResult q = vsi({"query", "--db", db, "--study", id, "--format", "json"});
  ASSERT_EQ(q.exit_code, 0) << q.err;
  const json out = json::parse(q.out);
  // Every job stores the section envelopes of the beam deck.
  for (const json& j : out.at("jobs")) {
    EXPECT_GT(j.at("envelopes").at("bending_moment_Nm").at("midspan").get<double>(), 0.0);
    EXPECT_GT(j.at("envelopes").at("support_reaction_N").at("support2").get<double>(), 0.0);
    EXPECT_GT(j.at("envelopes").at("support_rotation_rad").at("support1").get<double>(), 0.0);
  }
  const json& effects = out.at("dynamic_increment").at("effects");
  const double L = 10.0;
  struct Expect {
    const char* train;
    const char* quantity;
    const char* location;
    double value;
  };
  // One axle P = 150 kN: PL/4 at midspan, P a (L - a)/L at a = L/4, P/2 and
  // P. Two axles P = 100 kN, 3 m apart: one on midspan, P (L - 3)/2; the
  // largest reaction P (2 - 3/L).
  const Expect expect[] = {
      {"one axle", "bending_moment_Nm", "midspan", 1.5e5 * L / 4},
      {"one axle", "bending_moment_Nm", "quarter", 1.5e5 * 2.5 * 7.5 / L},
      {"one axle", "shear_force_N", "midspan", 1.5e5 / 2},
      {"one axle", "support_reaction_N", "support1", 1.5e5},
      {"two axles", "bending_moment_Nm", "midspan", 1e5 * (L - 3) / 2},
      {"two axles", "support_reaction_N", "support2", 1e5 * (2 - 3 / L)},
  };
  for (const Expect& e : expect) {
    const json* found = find_effect(effects, e.train, e.quantity, e.location);
    ASSERT_NE(found, nullptr) << e.train << " " << e.quantity << " " << e.location;
    EXPECT_NEAR(found->at("static").get<double>(), e.value, 1e-9 * e.value) << e.quantity << " " << e.location;
    const double dyn = found->at("dynamic").get<double>();
    EXPECT_NEAR(found->at("phi_dyn_prime").get<double>(), dyn / e.value - 1, 1e-9);
    // At 100-200 km/h on a 10 m span the dynamic effect is of the order of
    // the static one (a loose sanity bound, not an accuracy claim).
    EXPECT_GT(dyn, 0.8 * e.value) << e.quantity << " " << e.location;
    EXPECT_LT(dyn, 2.0 * e.value) << e.quantity << " " << e.location;
  }
  EXPECT_NE(find_effect(effects, "one axle", "deck_displacement_m", "midspan"), nullptr);
}

}  // namespace
}  // namespace railvsi::test

// The dt self-check's verdict per key quantity: a change beyond the
// tolerance is flagged, and so is a value that appears or vanishes at dt/2
// (no relative change exists, so it can never pass as converged).
#include <gtest/gtest.h>

#include "price/dt_self_check.hpp"

namespace railvsi {
namespace {

TEST(DtSelfCheck, FlagsAChangeAboveTheToleranceAndAValueThatAppearsOrVanishes) {
  JobEnvelopes at_dt, at_half;
  at_dt.max_abs_displacement_m = 1.000e-3;
  at_half.max_abs_displacement_m = 1.005e-3;  // -0.4975 %: within 1 %
  at_dt.max_abs_acceleration_mps2 = 2.0;
  at_half.max_abs_acceleration_mps2 = 2.1;  // -4.76 %
  at_dt.max_contact_loss_s = 0.0;
  at_half.max_contact_loss_s = 0.002;  // a loss only at dt/2: -100 %
  at_dt.min_contact_force_N = 1000.0;
  at_half.min_contact_force_N = 0.0;  // reference 0, value not: no relative change
  at_half.max_abs_carbody_acceleration_mps2 = 0.1;  // absent at dt
  const DtSelfCheck c = dt_self_check(at_dt, at_half, 1e-3, 5e-4, 0.01);
  ASSERT_EQ(c.rows.size(), 5u);  // the quantities absent from both runs left out
  const auto row = [&](const std::string& q) -> const DtCheckRow& {
    for (const DtCheckRow& r : c.rows)
      if (r.quantity == q) return r;
    throw std::runtime_error(q);
  };
  EXPECT_DOUBLE_EQ(*row("deck_displacement_m").relative_change, (1.000e-3 - 1.005e-3) / 1.005e-3);
  EXPECT_FALSE(row("deck_displacement_m").above_tolerance);
  EXPECT_DOUBLE_EQ(*row("deck_acceleration_mps2").relative_change, (2.0 - 2.1) / 2.1);
  EXPECT_TRUE(row("deck_acceleration_mps2").above_tolerance);
  EXPECT_EQ(*row("contact_loss_s").relative_change, -1.0);
  EXPECT_TRUE(row("contact_loss_s").above_tolerance);
  EXPECT_FALSE(row("min_contact_force_N").relative_change.has_value());
  EXPECT_TRUE(row("min_contact_force_N").above_tolerance);
  EXPECT_FALSE(row("carbody_acceleration_mps2").relative_change.has_value());
  EXPECT_TRUE(row("carbody_acceleration_mps2").above_tolerance);
  EXPECT_TRUE(c.any_above());
  const std::vector<RunWarning> w = dt_self_check_warnings(c);
  ASSERT_EQ(w.size(), 4u);
  for (const RunWarning& x : w) EXPECT_EQ(x.code, "dt_self_check");
  EXPECT_NE(w[0].message.find("deck_acceleration_mps2 changes -4.76 %"), std::string::npos) << w[0].message;
  // The factor: |change| / tolerance.
  ASSERT_TRUE(w[0].factor.has_value());
  EXPECT_DOUBLE_EQ(*w[0].factor, (0.1 / 2.1) / 0.01);
  const nlohmann::ordered_json j = dt_self_check_json(c);
  EXPECT_FALSE(j.at("converged").get<bool>());
  EXPECT_EQ(j.at("quantities").at(2).at("quantity"), "min_contact_force_N");
  EXPECT_TRUE(j.at("quantities").at(2).at("relative_change").is_null());
}

TEST(DtSelfCheck, EqualRunsAreConverged) {
  JobEnvelopes e;
  e.max_abs_displacement_m = 1e-3;
  e.max_abs_acceleration_mps2 = 0.0;
  const DtSelfCheck c = dt_self_check(e, e, 1e-3, 5e-4, 0.01);
  ASSERT_EQ(c.rows.size(), 2u);
  for (const DtCheckRow& r : c.rows) EXPECT_EQ(r.relative_change, 0.0) << r.quantity;
  EXPECT_FALSE(c.any_above());
  EXPECT_TRUE(dt_self_check_warnings(c).empty());
}

}  // namespace
}  // namespace railvsi

// The time step of a job (results/planning/time_step_policy.hpp). Expected
// steps are worked out here from the bounds' definitions and the ladder
// written out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/test_scenes.hpp"
#include "generators/bridge_2d.hpp"
#include "planning/time_step_policy.hpp"

namespace railvsi {
namespace {

// 20 m simply supported beam, f0 = 5 Hz, f3 = 9 f0 = 45 Hz, 0.25 m elements:
// f_cut = 45 Hz needs 1/(20 x 45) = 1.111 ms; the wheel travel bound is
// 0.25 x 0.25 m / v, which binds above 0.0625 / 1.111e-3 = 56.25 m/s (202.5 km/h).
std::shared_ptr<const StructureModel> beam_20m() {
  Bridge2dOptions b;
  b.spans_m = {20.0};
  b.deck_first_frequency_hz = 5.0;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.02;
  b.element_length_m = 0.25;
  return make_bridge_2d(b);
}

Train one_force() {
  Train t;
  t.name = "force";
  t.moving_forces = {{0.0, 170e3}};
  return t;
}

constexpr double kLadder[] = {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5};

double expected_rung(double required_s) {
  for (double dt : kLadder)
    if (dt <= required_s) return dt;
  return 0.0;
}

TimeStepChoice at_kmh(double speed_kmh) {
  return choose_time_step(*beam_20m(), one_force(), speed_kmh / 3.6, ContactOptions{}, 5.0, 45.0);
}

TEST(TimeStepPolicy, BindingConstraintSwitchesFromCodeFrequencyToWheelTravelWithSpeed) {
  const TimeStepChoice slow = at_kmh(200.0);
  EXPECT_EQ(slow.binding, "code frequency");
  EXPECT_NEAR(slow.required_dt_s, 1.0 / (20.0 * 45.0), 1e-15);
  EXPECT_DOUBLE_EQ(slow.dt_s, 1e-3);
  EXPECT_EQ(slow.ladder_k, 1);

  const TimeStepChoice fast = at_kmh(300.0);
  EXPECT_EQ(fast.binding, "wheel travel");
  EXPECT_NEAR(fast.required_dt_s, 0.25 * 0.25 / (300.0 / 3.6), 1e-15);
  EXPECT_DOUBLE_EQ(fast.dt_s, 5e-4);
  EXPECT_EQ(fast.ladder_k, 2);
}

TEST(TimeStepPolicy, ChoiceIsTheLargestLadderRungBelowTheRequirement) {
  for (double kmh = 60.0; kmh <= 420.0; kmh += 10.0) {
    const TimeStepChoice c = at_kmh(kmh);
    const double required = std::min(1.0 / (20.0 * 45.0), 0.25 * 0.25 / (kmh / 3.6));
    EXPECT_NEAR(c.required_dt_s, required, 1e-15) << kmh;
    EXPECT_EQ(c.dt_s, expected_rung(required)) << kmh;
    EXPECT_EQ(std::ldexp(c.dt_s, c.ladder_k), 2e-3) << kmh;  // exactly on the ladder
  }
}

TEST(TimeStepPolicy, SpeedsInOneLadderIntervalShareTheStep) {
  // 250 and 300 km/h need 0.90 and 0.75 ms (wheel travel): both get 0.5 ms,
  // so they share a factorization; 120 and 200 km/h both get 1 ms.
  EXPECT_NE(at_kmh(250.0).required_dt_s, at_kmh(300.0).required_dt_s);
  EXPECT_EQ(at_kmh(250.0).dt_s, at_kmh(300.0).dt_s);
  EXPECT_EQ(at_kmh(120.0).dt_s, at_kmh(200.0).dt_s);
  EXPECT_NE(at_kmh(200.0).dt_s, at_kmh(300.0).dt_s);
}

TEST(TimeStepPolicy, ReasonNamesEveryBoundWithItsNumbersAndTheBindingOne) {
  const TimeStepChoice c = at_kmh(300.0);
  EXPECT_NE(c.reason.find("f_cut = max(30, 1.5 f0 = 7.5, f3 = 45.0) = 45.0 Hz at 20 steps/period needs 1.11e-03 s"),
            std::string::npos)
      << c.reason;
  EXPECT_NE(c.reason.find("wheel travel 0.25 x 0.250 m element at 83.3 m/s needs 7.50e-04 s"), std::string::npos)
      << c.reason;
  EXPECT_NE(c.reason.find("binding: wheel travel; ladder 2.0e-03 s / 2^2 = 5.000e-04 s"), std::string::npos)
      << c.reason;
}

TEST(TimeStepPolicy, CodeFrequencyIsAtLeast30Hz) {
  // A 3 Hz deck with f3 unknown: f_cut = 30 Hz needs 1.667 ms -> 1 ms.
  const TimeStepChoice c = choose_time_step(*beam_20m(), one_force(), 100.0 / 3.6, ContactOptions{}, 3.0, 0.0);
  EXPECT_NEAR(c.required_dt_s, 1.0 / 600.0, 1e-15);
  EXPECT_DOUBLE_EQ(c.dt_s, 1e-3);
}

TEST(TimeStepPolicy, HertzContactFrequencyOfAnIce3Coach) {
  // Symmetric coach of 62 t on four wheelsets: Q = 62000 g / 4 per contact
  // (both rails lumped, n = 2), G = 3.86e-8 R^-0.115 with R = 0.46 m,
  // k_H = 1.5 n (Q/n)^(1/3) / G, wheelset mass 1800 kg.
  Train train;
  train.vehicles.push_back({make_car_2d(testing::ice3_coach()), 0.0});
  ContactOptions hertz;
  const double Q = 62000.0 * 9.81 / 4.0;
  const double G = 3.86e-8 * std::pow(0.46, -0.115);
  const double k = 1.5 * 2.0 * std::cbrt(Q / 2.0) / G;
  const double f_H = std::sqrt(k / 1800.0) / (2.0 * std::numbers::pi);
  EXPECT_NEAR(highest_contact_frequency_hz(train, hertz), f_H, 1e-9 * f_H);
  EXPECT_NEAR(f_H, 206.0, 1.0);  // the order of magnitude the policy is justified with

  ContactOptions rigid;
  rigid.law = "rigid";
  rigid.unilateral = false;
  EXPECT_EQ(highest_contact_frequency_hz(train, rigid), 0.0);
  EXPECT_EQ(highest_contact_frequency_hz(one_force(), hertz), 0.0);

  // On the beam at 200 km/h the contact binds: 1 / (10 f_H) = 0.485 ms -> 0.25 ms.
  const TimeStepChoice c = choose_time_step(*beam_20m(), train, 200.0 / 3.6, hertz, 5.0, 45.0);
  EXPECT_EQ(c.binding, "contact frequency");
  EXPECT_NEAR(c.required_dt_s, 1.0 / (10.0 * f_H), 1e-12);
  EXPECT_DOUBLE_EQ(c.dt_s, 2.5e-4);
  // A rigid contact drops that bound: back to the code frequency.
  EXPECT_EQ(choose_time_step(*beam_20m(), train, 200.0 / 3.6, rigid, 5.0, 45.0).binding, "code frequency");
}

TEST(TimeStepPolicy, RejectsNegativeOrNonFiniteArguments) {
  EXPECT_THROW(at_kmh(-10.0), std::invalid_argument);
  EXPECT_THROW(choose_time_step(*beam_20m(), one_force(), 50.0, ContactOptions{}, std::nan(""), 45.0),
               std::invalid_argument);
  TimeStepPolicy p;
  p.steps_per_period = 0.0;
  EXPECT_THROW(choose_time_step(*beam_20m(), one_force(), 50.0, ContactOptions{}, 5.0, 45.0, p),
               std::invalid_argument);
}

}  // namespace
}  // namespace railvsi

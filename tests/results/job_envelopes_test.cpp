// Envelopes of one job (results/envelopes/job_envelopes.hpp): synthetic
// results with known maxima, and real runs of the engine.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "engine/test_scenes.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/envelope_rows.hpp"
#include "envelopes/job_envelopes.hpp"
#include "generators/bridge_2d.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 2.5e-4;

// Two deck points with accelerations of known content, three wheels (two
// evaluated, one never in the evaluation window), one car body.
Result synthetic_run() {
  Result r;
  RunSummary& s = r.summary;
  s.points = {{"p1", 5.0, 0.003, 1.39, std::nullopt, std::nullopt}, {"p2", 10.0, 0.004, 0.5, std::nullopt, std::nullopt}};
  s.wheels = {{"v1_w1", 80e3, 20e3, 0.75, 0.0, true},
              {"v1_w2", 80e3, 0.0, 1.0, 0.012, true},
              {"v1_w3", 80e3, 0.0, 0.0, 0.0, false}};
  s.max_abs_carbody_acceleration_mps2 = 0.3;
  s.steps = 8000;
  s.dt_s = kDt;
  s.newton_iterations = 16123;
  s.max_newton_iterations_in_step = 4;
  s.fidelity.model = "interaction";
  s.fidelity.contact_law = "hertz";
  s.fidelity.unilateral = true;
  Histories& h = r.histories;
  h.point_names = {"p1", "p2"};
  h.deck_acceleration_mps2.resize(2);
  h.deck_displacement_m.resize(2);
  for (long k = 0; k <= s.steps; ++k) {
    const double t = k * kDt;
    h.t_s.push_back(t);
    // p1: 1.0 at 5 Hz (kept) plus 0.4 at 150 Hz (removed); p2: 0.5 at 8 Hz.
    h.deck_acceleration_mps2[0].push_back(std::sin(2 * kPi * 5.0 * t + 0.2) + 0.4 * std::sin(2 * kPi * 150.0 * t));
    h.deck_acceleration_mps2[1].push_back(0.5 * std::sin(2 * kPi * 8.0 * t + 1.0));
    h.deck_displacement_m[0].push_back(0.0);
    h.deck_displacement_m[1].push_back(0.0);
  }
  return r;
}

TEST(JobEnvelopes, KnownMaximaOfASyntheticRun) {
  const JobEnvelopes e = compute_envelopes(synthetic_run(), kDt, 1, 30.0);
  ASSERT_TRUE(e.ok()) << e.message;
  EXPECT_TRUE(e.notes.empty());
  ASSERT_EQ(e.points.size(), 2u);
  EXPECT_EQ(e.points[0].name, "p1");
  EXPECT_DOUBLE_EQ(e.points[0].x_m, 5.0);
  EXPECT_DOUBLE_EQ(*e.points[0].max_abs_displacement_m, 0.003);
  EXPECT_DOUBLE_EQ(*e.points[1].max_abs_displacement_m, 0.004);
  EXPECT_DOUBLE_EQ(*e.max_abs_displacement_m, 0.004);
  EXPECT_DOUBLE_EQ(*e.points[0].max_abs_acceleration_unfiltered_mps2, 1.39);
  EXPECT_DOUBLE_EQ(*e.max_abs_acceleration_unfiltered_mps2, 1.39);
  // The 150 Hz part is gone, the 5 Hz and 8 Hz sines keep their amplitude.
  EXPECT_NEAR(*e.points[0].max_abs_acceleration_mps2, 1.0, 0.005);
  EXPECT_NEAR(*e.points[1].max_abs_acceleration_mps2, 0.5, 0.0025);
  EXPECT_EQ(*e.max_abs_acceleration_mps2, *e.points[0].max_abs_acceleration_mps2);
  EXPECT_DOUBLE_EQ(e.cutoff_hz, 30.0);
  EXPECT_NE(e.filter.find("Butterworth"), std::string::npos);

  ASSERT_EQ(e.wheels.size(), 3u);
  EXPECT_DOUBLE_EQ(*e.wheels[0].unloading_ratio, 0.75);
  EXPECT_DOUBLE_EQ(*e.wheels[1].contact_loss_s, 0.012);
  EXPECT_FALSE(e.wheels[2].evaluated);
  EXPECT_DOUBLE_EQ(*e.wheels[2].static_load_N, 80e3);
  EXPECT_FALSE(e.wheels[2].min_force_N.has_value());
  EXPECT_FALSE(e.wheels[2].unloading_ratio.has_value());
  EXPECT_DOUBLE_EQ(*e.max_unloading_ratio, 1.0);
  EXPECT_DOUBLE_EQ(*e.max_contact_loss_s, 0.012);
  EXPECT_DOUBLE_EQ(*e.min_contact_force_N, 0.0);
  EXPECT_DOUBLE_EQ(*e.max_abs_carbody_acceleration_mps2, 0.3);

  EXPECT_EQ(e.steps, 8000);
  EXPECT_EQ(e.newton_iterations, 16123);
  EXPECT_EQ(e.max_newton_iterations_in_step, 4);
  EXPECT_DOUBLE_EQ(e.dt_s, kDt);
  EXPECT_EQ(e.fidelity.contact_law, "hertz");
}

TEST(JobEnvelopes, KeepTheSummarysRunRecordAtTheirOwnDt) {
  Result r = synthetic_run();
  RunSummary& s = r.summary;
  s.wall_s = 1.25;
  s.setup_s = 0.5;
  s.energy_residual = 3e-4;
  s.warnings = {{"dt_above_policy", "the step is above the policy's", 0.1, std::nullopt, 2.0}};
  s.fidelity.reasons = {"pinned in the scene"};
  const JobEnvelopes e = compute_envelopes(r, 2.0 * kDt, 1, 30.0);
  EXPECT_EQ(e.steps, s.steps);
  EXPECT_EQ(e.newton_iterations, s.newton_iterations);
  EXPECT_EQ(e.max_newton_iterations_in_step, s.max_newton_iterations_in_step);
  EXPECT_EQ(e.wall_s, 1.25);
  EXPECT_EQ(e.setup_s, 0.5);
  EXPECT_EQ(e.energy_residual, 3e-4);
  ASSERT_EQ(e.warnings.size(), 1u);
  EXPECT_EQ(e.warnings[0].code, "dt_above_policy");
  EXPECT_EQ(*e.warnings[0].factor, 2.0);
  EXPECT_EQ(e.fidelity.reasons, s.fidelity.reasons);
  EXPECT_EQ(e.dt_s, 2.0 * kDt);  // the envelopes' step, not the summary's
  // A time that cannot be stored as a number is stored as 0.
  s.wall_s = std::numeric_limits<double>::quiet_NaN();
  s.setup_s = std::numeric_limits<double>::infinity();
  const JobEnvelopes f = compute_envelopes(r, kDt, 1, 30.0);
  EXPECT_EQ(f.wall_s, 0.0);
  EXPECT_EQ(f.setup_s, 0.0);
}

TEST(JobEnvelopes, NonFiniteValueIsLeftOutNamedAndTheRunIsNotOk) {
  Result r = synthetic_run();
  r.summary.points[1].max_abs_displacement_m = std::numeric_limits<double>::quiet_NaN();
  r.summary.wheels[0].min_force_N = std::numeric_limits<double>::infinity();
  const JobEnvelopes e = compute_envelopes(r, kDt, 1, 30.0);
  EXPECT_EQ(e.status, "diverged");
  EXPECT_NE(e.message.find("deck displacement at p2"), std::string::npos) << e.message;
  EXPECT_FALSE(e.points[1].max_abs_displacement_m.has_value());
  EXPECT_FALSE(e.max_abs_displacement_m.has_value());  // the maximum of a set with a hole is unknown
  EXPECT_DOUBLE_EQ(*e.points[0].max_abs_displacement_m, 0.003);
  EXPECT_FALSE(e.wheels[0].min_force_N.has_value());
  EXPECT_FALSE(e.min_contact_force_N.has_value());
  EXPECT_EQ(e.notes.size(), 2u);
}

TEST(JobEnvelopes, NanInTheAccelerationHistoryLeavesTheFilteredValueOut) {
  Result r = synthetic_run();
  r.histories.deck_acceleration_mps2[1][4000] = std::numeric_limits<double>::quiet_NaN();
  const JobEnvelopes e = compute_envelopes(r, kDt, 1, 30.0);
  EXPECT_EQ(e.status, "diverged");
  EXPECT_FALSE(e.points[1].max_abs_acceleration_mps2.has_value());
  EXPECT_FALSE(e.max_abs_acceleration_mps2.has_value());
  EXPECT_TRUE(e.points[0].max_abs_acceleration_mps2.has_value());
}

TEST(JobEnvelopes, FailedRunKeepsItsStatusAndMessage) {
  Result r = synthetic_run();
  r.status = Status(StatusCode::kNoConvergence, "step 12: Newton did not converge");
  const JobEnvelopes e = compute_envelopes(r, kDt, 1, 30.0);
  EXPECT_EQ(e.status, "no_convergence");
  EXPECT_EQ(e.message, "step 12: Newton did not converge");
  EXPECT_FALSE(e.ok());
}

TEST(JobEnvelopes, DecimatedHistoriesGiveNoFilteredValueAndSayWhy) {
  Result r = synthetic_run();
  Histories& h = r.histories;
  Histories every_other;
  every_other.point_names = h.point_names;
  every_other.deck_acceleration_mps2.resize(2);
  for (std::size_t k = 0; k < h.t_s.size(); k += 2) {
    every_other.t_s.push_back(h.t_s[k]);
    for (int p = 0; p < 2; ++p) every_other.deck_acceleration_mps2[p].push_back(h.deck_acceleration_mps2[p][k]);
  }
  r.histories = every_other;
  const JobEnvelopes e = compute_envelopes(r, kDt, 2, 30.0);
  EXPECT_TRUE(e.ok());
  EXPECT_FALSE(e.points[0].max_abs_acceleration_mps2.has_value());
  EXPECT_FALSE(e.max_abs_acceleration_mps2.has_value());
  ASSERT_EQ(e.notes.size(), 1u);
  EXPECT_NE(e.notes[0].find("history_stride = 1"), std::string::npos) << e.notes[0];
  EXPECT_DOUBLE_EQ(*e.max_abs_acceleration_unfiltered_mps2, 1.39);  // from the summary: every step
}

TEST(JobEnvelopes, MovingForcesHaveNoWheelOrCarBodyValues) {
  Result r = synthetic_run();
  r.summary.wheels.clear();
  const JobEnvelopes e = compute_envelopes(r, kDt, 1, 30.0);
  EXPECT_TRUE(e.wheels.empty());
  EXPECT_FALSE(e.max_unloading_ratio.has_value());
  EXPECT_FALSE(e.max_contact_loss_s.has_value());
  EXPECT_FALSE(e.min_contact_force_N.has_value());
  EXPECT_FALSE(e.max_abs_carbody_acceleration_mps2.has_value());
}

// Every envelope value, bit for bit (wall and setup times are measurements).
void expect_identical(const JobEnvelopes& a, const JobEnvelopes& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.notes, b.notes);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t p = 0; p < a.points.size(); ++p) {
    EXPECT_EQ(a.points[p].max_abs_displacement_m, b.points[p].max_abs_displacement_m);
    EXPECT_EQ(a.points[p].max_abs_acceleration_mps2, b.points[p].max_abs_acceleration_mps2);
    EXPECT_EQ(a.points[p].max_abs_acceleration_unfiltered_mps2, b.points[p].max_abs_acceleration_unfiltered_mps2);
  }
  ASSERT_EQ(a.wheels.size(), b.wheels.size());
  for (std::size_t w = 0; w < a.wheels.size(); ++w) {
    EXPECT_EQ(a.wheels[w].min_force_N, b.wheels[w].min_force_N);
    EXPECT_EQ(a.wheels[w].unloading_ratio, b.wheels[w].unloading_ratio);
    EXPECT_EQ(a.wheels[w].contact_loss_s, b.wheels[w].contact_loss_s);
  }
  EXPECT_EQ(a.max_abs_carbody_acceleration_mps2, b.max_abs_carbody_acceleration_mps2);
  EXPECT_EQ(a.newton_iterations, b.newton_iterations);
  EXPECT_EQ(a.steps, b.steps);
}

// A 170 kN force at 200 km/h over a 20 m simply supported beam, f1 = 5 Hz.
Scene moving_force_on_20m_beam() {
  Bridge2dOptions b;
  b.spans_m = {20.0};
  b.deck_first_frequency_hz = 5.0;
  b.deck_mass_kg_per_m = 15000.0;
  b.damping_ratio = 0.02;
  Scene s;
  s.structure = make_bridge_2d(b);
  s.train.name = "one force";
  s.train.moving_forces = {{0.0, 170e3}};
  s.speed_mps = 200.0 / 3.6;
  s.analysis.dt_s = 5e-4;
  return s;
}

TEST(JobEnvelopes, MovingForceOnABeamFilteredBelowUnfilteredDisplacementAsTheRunAndDeterministic) {
  const Scene scene = moving_force_on_20m_beam();
  const double cutoff = code_cutoff_hz(5.0, 45.0);  // f3 = 9 f1 for a simply supported beam
  const Result r1 = Simulation(scene).run();
  const Result r2 = Simulation(scene).run();
  ASSERT_TRUE(r1.status.ok()) << r1.status.message();
  const JobEnvelopes e = compute_envelopes(r1, scene.analysis.dt_s, 1, cutoff);
  ASSERT_TRUE(e.ok()) << e.message;
  ASSERT_FALSE(e.points.empty());
  for (std::size_t p = 0; p < e.points.size(); ++p) {
    const PointEnvelope& pe = e.points[p];
    EXPECT_LE(*pe.max_abs_acceleration_mps2, *pe.max_abs_acceleration_unfiltered_mps2) << pe.name;
    EXPECT_GT(*pe.max_abs_acceleration_mps2, 0.0);
    EXPECT_EQ(*pe.max_abs_displacement_m, r1.summary.points[p].max_abs_displacement_m);
    // ... which is the largest |u| of the stored history (every step is stored).
    double u = 0.0;
    for (double v : r1.histories.deck_displacement_m[p]) u = railvsi::testing::worst_of(u, std::abs(v));
    EXPECT_EQ(*pe.max_abs_displacement_m, u);
  }
  EXPECT_EQ(*e.max_abs_displacement_m, r1.summary.max_abs_displacement_m);
  expect_identical(e, compute_envelopes(r2, scene.analysis.dt_s, 1, cutoff));
}

TEST(JobEnvelopes, CoachLosingContactGivesTheSameEnvelopesTwice) {
  // The hard case for determinism: contact loss and re-impact (active set).
  Scene scene = testing::small_viaduct_with_dip(300.0, 0.004);
  scene.analysis.duration_s = 0.25;  // the dip and the landing
  const Result r1 = Simulation(scene).run();
  const Result r2 = Simulation(scene).run();
  const JobEnvelopes e1 = compute_envelopes(r1, scene.analysis.dt_s, 1, 30.0);
  ASSERT_TRUE(e1.ok()) << e1.message;
  ASSERT_TRUE(e1.max_contact_loss_s.has_value());
  EXPECT_GT(*e1.max_contact_loss_s, 0.0);
  EXPECT_DOUBLE_EQ(*e1.max_unloading_ratio, 1.0);
  expect_identical(e1, compute_envelopes(r2, scene.analysis.dt_s, 1, 30.0));
}

}  // namespace
}  // namespace railvsi

namespace railvsi {
namespace {

// Section forces of a beam deck become rows per point and per support, with
// the overall maximum; a structure without them writes no such row and a
// note says why (never a 0).
TEST(JobEnvelopes, SectionForcesBecomeRowsOnlyWhereDefined) {
  Result r = synthetic_run();
  r.summary.points[0].max_abs_bending_moment_Nm = 2.0e6;
  r.summary.points[1].max_abs_bending_moment_Nm = 3.0e6;
  r.summary.points[0].max_abs_shear_force_N = 4.0e5;
  r.summary.points[1].max_abs_shear_force_N = 1.0e5;
  r.summary.supports = {{"support1", 0.0, 2.5e5, 1.5e-3}, {"support2", 20.0, 2.4e5, 1.4e-3}};
  const JobEnvelopes e = compute_envelopes(r, kDt, 1, 30.0);
  const auto value = [&](const std::vector<EnvelopeRow>& rows, const std::string& q, const std::string& loc) {
    for (const EnvelopeRow& row : rows)
      if (row.quantity == q && row.location == loc) return row.value;
    return std::optional<double>{-1.0};  // no such row
  };
  const auto rows = envelope_rows(e);
  EXPECT_EQ(value(rows, "bending_moment_Nm", "p1"), 2.0e6);
  EXPECT_EQ(value(rows, "bending_moment_Nm", ""), 3.0e6);
  EXPECT_EQ(value(rows, "shear_force_N", ""), 4.0e5);
  EXPECT_EQ(value(rows, "support_reaction_N", "support2"), 2.4e5);
  EXPECT_EQ(value(rows, "support_rotation_rad", "support1"), 1.5e-3);
  EXPECT_EQ(extreme_of("support_reaction_N"), Extreme::kMax);

  Result none = synthetic_run();
  none.summary.section_forces_note = "no beam deck";
  const JobEnvelopes n = compute_envelopes(none, kDt, 1, 30.0);
  ASSERT_EQ(n.notes.size(), 1u);
  EXPECT_NE(n.notes[0].find("no beam deck"), std::string::npos);
  for (const EnvelopeRow& row : envelope_rows(n))
    EXPECT_TRUE(row.quantity.find("moment") == std::string::npos && row.quantity.find("shear") == std::string::npos &&
                row.quantity.find("support") == std::string::npos)
        << row.quantity;
}

}  // namespace
}  // namespace railvsi

// The hard-case suite (docs/verification.md "Hard cases"): scenes that used to print
// "ok" on garbage or that stress the contact, the integrator and the
// inputs. Each asserts no NaN, the expected status and warnings, a bounded
// energy residual and, where the run claims a result, agreement between dt
// and a finer dt on deck displacement, filtered deck acceleration, dQ/Q and
// car-body acceleration within a stated tolerance (measured values in the
// comments; tolerances about 1.5-3x the measured difference).
//
// Each case prints one line of the table in docs/verification.md (scene, status, warnings,
// energy residual, dt-convergence).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "envelopes/code_filter.hpp"
#include "generators/deck_3d.hpp"
#include "envelopes/job_envelopes.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/rung_runner.hpp"
#include "planning/time_step_policy.hpp"
#include "planning/time_step_warnings.hpp"
#include "planning/wheel_value_warnings.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

json one_coach() {
  std::ifstream in(train_library_dir() / "ICE3.json");
  json ice3 = json::parse(in);
  json coach = ice3.at("vehicles").at(0);
  coach.erase("count");
  return {{"name", "ICE3 coach"}, {"vehicles", json::array({coach})}};
}

// Two 15 m spans, f0 about 5 Hz, ballasted track (short approach for one
// coach; an exit long enough that the coach's last wheels have left the
// evaluation window before its first run off the rail end), Hertz contact.
json two_span_scene(double speed_kmh, double dt_s) {
  return {{"structure",
           {{"generator", "bridge-2d"},
            {"spans_m", {15.0, 15.0}},
            {"deck", {{"EI_Nm2", 1.2e10}, {"mass_kg_per_m", 15000}}},
            {"damping", {{"ratio", 0.02}}},
            {"element_length_m", 0.6},
            {"track", {{"approach_m", 36.0}, {"exit_m", 36.0}}}}},
          {"train", one_coach()},
          {"speed_kmh", speed_kmh},
          {"analysis", {{"dt_s", dt_s}, {"contact", {{"law", "hertz"}}}}},
          {"outputs", {{"points", {{{"name", "mid1"}, {"x_m", 7.5}}, {{"name", "mid2"}, {"x_m", 22.5}}}}}}};
}

// One simply supported span under moving forces.
json moving_force_scene(double span_m, double EI, double mass, double ratio, double speed_kmh, double dt_s,
                        int axles, double spacing_m) {
  json forces = json::array();
  for (int i = 0; i < axles; ++i) forces.push_back({{"offset_m", i * spacing_m}, {"load_N", 170000.0}});
  return {{"structure",
           {{"generator", "bridge-2d"},
            {"spans_m", {span_m}},
            {"deck", {{"EI_Nm2", EI}, {"mass_kg_per_m", mass}}},
            {"damping", {{"ratio", ratio}}},
            {"element_length_m", span_m / 20.0},
            {"track", nullptr}}},
          {"train", {{"name", "axles"}, {"moving_forces", forces}}},
          {"speed_kmh", speed_kmh},
          {"analysis", {{"dt_s", dt_s}}},
          {"outputs", {{"points", {{{"name", "mid"}, {"x_m", span_m / 2}}}}}}};
}

struct Outcome {
  Result result;
  JobEnvelopes env;
  std::set<std::string> codes;
};

Outcome run(const Scene& scene, double cutoff_hz) {
  const Simulation sim(scene);
  Outcome o;
  o.result = sim.run();
  for (RunWarning& w : time_step_warnings(scene, cutoff_hz)) o.result.summary.warnings.push_back(std::move(w));
  for (RunWarning& w : wheel_value_warnings(scene, o.result.summary, cutoff_hz))
    o.result.summary.warnings.push_back(std::move(w));
  o.env = compute_envelopes(o.result, scene.analysis.dt_s, scene.analysis.history_stride, cutoff_hz);
  for (const RunWarning& w : o.result.summary.warnings) o.codes.insert(w.code);
  return o;
}

Outcome run(const json& doc, double cutoff_hz) {
  return run(parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs", "hard case"), cutoff_hz);
}

// The scene through its fidelity (run_planned, as vsi simulate runs it),
// with the warnings vsi simulate adds for the run as it ran.
Outcome planned(const json& doc, double cutoff_hz) {
  const Scene scene = parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs", "hard case");
  Outcome o;
  o.result = run_planned(scene, deck_frequencies(*scene.structure));
  const Scene ran = scene_as_run(scene, o.result.summary);
  for (RunWarning& w : time_step_warnings(ran, cutoff_hz)) o.result.summary.warnings.push_back(std::move(w));
  for (RunWarning& w : wheel_value_warnings(ran, o.result.summary, cutoff_hz))
    o.result.summary.warnings.push_back(std::move(w));
  o.env = compute_envelopes(o.result, o.result.summary.dt_s, ran.analysis.history_stride, cutoff_hz);
  for (const RunWarning& w : o.result.summary.warnings) o.codes.insert(w.code);
  return o;
}

// Relative difference; NaN, which fails every comparison, when either run
// lacks the value (two missing values are not an agreement).
double rel(std::optional<double> a, std::optional<double> b) {
  if (!a || !b) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(*a - *b) / std::max(std::abs(*b), 1e-12);
}

struct Convergence {
  double displacement = 0, acceleration = 0, unloading = 0, carbody = 0;
  bool wheels = true;  // false: moving forces, no wheel or car-body values to compare
};

Convergence compare(const Outcome& coarse, const Outcome& fine) {
  Convergence c;
  c.displacement = rel(coarse.env.max_abs_displacement_m, fine.env.max_abs_displacement_m);
  c.acceleration = rel(coarse.env.max_abs_acceleration_mps2, fine.env.max_abs_acceleration_mps2);
  c.wheels = !coarse.result.summary.static_wheel_load_N.empty();
  if (c.wheels) {
    c.unloading = rel(coarse.env.max_unloading_ratio, fine.env.max_unloading_ratio);
    c.carbody = rel(coarse.env.max_abs_carbody_acceleration_mps2, fine.env.max_abs_carbody_acceleration_mps2);
  }
  return c;
}

void expect_finite(const Outcome& o) {
  const RunSummary& s = o.result.summary;
  EXPECT_TRUE(std::isfinite(s.max_abs_displacement_m));
  EXPECT_TRUE(std::isfinite(s.max_abs_acceleration_mps2));
  for (const auto& h : o.result.histories.deck_displacement_m)
    for (double v : h) ASSERT_TRUE(std::isfinite(v));
  for (const auto& h : o.result.histories.contact_force_N)
    for (double v : h) ASSERT_TRUE(std::isfinite(v));
  EXPECT_TRUE(std::isfinite(s.energy_residual));
}

std::string codes_text(const Outcome& o) {
  std::string t;
  for (const std::string& c : o.codes) t += (t.empty() ? "" : ", ") + c;
  return t.empty() ? "-" : t;
}

// One row of the table in docs/verification.md.
void table_row(const std::string& scene, const Outcome& o, const std::string& convergence) {
  std::cout << fmt::format("| {} | {} | {} | {:.1e} | {} |\n", scene, o.result.status.name(), codes_text(o),
                           o.result.summary.energy_residual, convergence);
}

std::string convergence_text(const Convergence& c, const char* ratio) {
  if (!c.wheels) return fmt::format("{}: w {:.3g} %, a_filt {:.3g} %", ratio, 100 * c.displacement, 100 * c.acceleration);
  return fmt::format("{}: w {:.3g} %, a_filt {:.3g} %, dQ/Q {:.3g} %, body {:.3g} %", ratio, 100 * c.displacement,
                     100 * c.acceleration, 100 * c.unloading, 100 * c.carbody);
}

// Tolerances of one claimed case, each at most 3x the difference measured
// (both stated beside the call).
struct Tolerances {
  double w, a, dq, body;
};

// A case that claims a result: ok, the listed warnings only, converged.
void claimed(const std::string& name, const json& coarse_doc, const json& fine_doc, double cutoff_hz,
             const std::set<std::string>& warnings, double energy_tol, const Tolerances& tol, const char* ratio,
             Outcome* coarse_out = nullptr) {
  const Outcome coarse = run(coarse_doc, cutoff_hz);
  const Outcome fine = run(fine_doc, cutoff_hz);
  expect_finite(coarse);
  expect_finite(fine);
  EXPECT_TRUE(coarse.result.status.ok()) << coarse.result.status.message();
  EXPECT_TRUE(fine.result.status.ok()) << fine.result.status.message();
  EXPECT_EQ(coarse.codes, warnings) << codes_text(coarse);
  EXPECT_LE(coarse.result.summary.energy_residual, energy_tol);
  EXPECT_LE(fine.result.summary.energy_residual, energy_tol);
  const Convergence c = compare(coarse, fine);
  EXPECT_LE(c.displacement, tol.w);
  EXPECT_LE(c.acceleration, tol.a);
  EXPECT_LE(c.unloading, tol.dq);
  EXPECT_LE(c.carbody, tol.body);
  table_row(name, coarse, convergence_text(c, ratio));
  if (coarse_out) *coarse_out = coarse;
}

json with_dt(json doc, double dt_s) {
  doc["analysis"]["dt_s"] = dt_s;
  return doc;
}

json with_irregularity(json doc, json irregularity) {
  doc["irregularity"] = std::move(irregularity);
  return doc;
}

json defect(const char* type, double x_m, double length_m, double depth_m) {
  return {{"defects", {{{"type", type}, {"x_m", x_m}, {"length_m", length_m}, {"depth_m", depth_m}}}}};
}

// f3 of a simply supported span is 9 f0; two equal spans have the same.
double ss_cutoff(double f0_hz) { return code_cutoff_hz(f0_hz, 9.0 * f0_hz); }
double f0_of(double L, double EI, double m) { return M_PI / (2 * L * L) * std::sqrt(EI / m); }

const double kTwoSpanCutoff = ss_cutoff(f0_of(15.0, 1.2e10, 15000));

TEST(HardCases, DeepDipLosesContactAndReimpacts) {
  const json doc = with_irregularity(two_span_scene(300, 2.5e-4), defect("dip", 10.0, 1.0, 0.020));
  Outcome coarse;
  // Measured dt 2.5e-4 vs 1.25e-4: see the table in docs/verification.md.
  claimed("deep dip 20 mm, Hertz, 300 km/h", doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, {"dt_above_policy"}, 1e-9,
          {5e-5, 0.015, 0.0, 2.5e-3}, "dt/2", &coarse);
  // Measured 2026-11-27: w 0.00194 %, a_filt 0.601 %, dQ/Q 0 (1 in both: the
  // contact is lost), body 0.0879 %. The policy's track bound (the wheel
  // lifts: 150 steps over the 1 m dip at 83.3 m/s, 8.0e-5 s) warns at 0.25 ms.
  EXPECT_GT(coarse.result.summary.contact_loss_s, 0.0);     // the wheel leaves the rail
  EXPECT_DOUBLE_EQ(coarse.result.summary.max_unloading_ratio, 1.0);
}

TEST(HardCases, FiveMillimetreStep) {
  const json profile = {{"x_m", {-400.0, 10.0, 10.01, 400.0}}, {"r_m", {0.0, 0.0, 0.005, 0.005}}};
  const json doc = with_irregularity(two_span_scene(300, 2.5e-4), profile);
  claimed("5 mm step up, Hertz, 300 km/h", doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, {"dt_above_policy"}, 1e-9,
          {7e-4, 9e-3, 0.0, 0.05}, "dt/2");
  // Measured 2026-11-27: w 0.0239 %, a_filt 0.322 %, dQ/Q 0, body 1.84 %. The
  // step rises over 0.01 m: the policy warns (its floor, 15.6 us, is above
  // the 3.6e-6 s it needs).
}

TEST(HardCases, Bump) {
  const json doc = with_irregularity(two_span_scene(300, 2.5e-4), defect("bump", 10.0, 2.0, 0.005));
  claimed("bump 5 mm over 2 m, Hertz, 300 km/h", doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, {}, 1e-9,
          {2e-4, 5e-3, 0.0, 5e-4}, "dt/2");  // measured w 0.0073 %, a_filt 0.193 %, dQ/Q 0, body 0.0188 %
}

TEST(HardCases, Fra1At400) {
  const json doc = with_irregularity(two_span_scene(400, 2.5e-4), {{"spectrum", "fra-1"}, {"seed", 1}});
  claimed("FRA 1, Hertz, 400 km/h", doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, {}, 1e-9,
          {8e-4, 6e-3, 0.0, 6e-4}, "dt/2");  // measured w 0.0269 %, a_filt 0.217 %, dQ/Q 0, body 0.0201 %
}

TEST(HardCases, GermanHighAt400) {
  const json doc = with_irregularity(two_span_scene(400, 2.5e-4), {{"spectrum", "german-high"}, {"seed", 1}});
  // dQ/Q converges slowest on the roughest profile at 400 km/h. Measured
  // 2026-11-27: w 0.00174 %, a_filt 0.0562 %, dQ/Q 4.10 %, body 0.00605 %.
  // A wheel keeps 52 % of its load on the rail: at the policy's step (0.25
  // ms) its Q min is +3.9 % off dt/4, and the run says so (wheel_values_dt).
  Outcome coarse;
  claimed("German high, Hertz, 400 km/h", doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, {"wheel_values_dt"}, 1e-9,
          {5e-5, 1.5e-3, 0.12, 1.8e-4}, "dt/2", &coarse);
  for (const RunWarning& w : coarse.result.summary.warnings)
    if (w.code == "wheel_values_dt") {
      ASSERT_TRUE(w.factor.has_value());
      EXPECT_DOUBLE_EQ(*w.factor, 2.0) << w.message;  // 0.25 ms against 0.5 x the policy's 0.25 ms
      EXPECT_NE(w.message.find("nonlinear Hertz on rung interaction/fe"), std::string::npos) << w.message;
    }
}

// Issue 33: a pinned unilateral linear Hertz over the German high profile
// at 400 km/h had an unconservative Q min and no warning. Against the full
// model (unilateral Hertz at dt/4 = 62.5 us), measured 2026-11-27: linear
// Hertz at the policy's 0.25 ms +2.54 % (Hertz at 0.25 ms +3.92 %: the step
// error), linear Hertz at dt/4 -1.43 % (its own law error); the planner's
// answer ("auto": repeated with unilateral Hertz at 0.125 ms) -0.13 %.
TEST(HardCases, PinnedLinearHertzOnGermanHighWarnsAndThePlannerIsWithinOnePercent) {
  json doc = with_irregularity(two_span_scene(400, 2.5e-4), {{"spectrum", "german-high"}, {"seed", 1}});
  json pinned = doc;
  pinned["analysis"]["contact"] = {{"law", "linear-hertz"}, {"unilateral", true}};
  pinned["fidelity"] = {{"model", "interaction"}, {"structure", "fe"}, {"contact_law", "linear-hertz"},
                        {"unilateral", true}};
  const Outcome linear = planned(pinned, kTwoSpanCutoff);
  json automatic = doc;
  automatic["fidelity"] = "auto";
  const Outcome planner = planned(automatic, kTwoSpanCutoff);
  const Result& auto_run = planner.result;
  const Outcome full = run(with_dt(doc, 6.25e-5), kTwoSpanCutoff);
  expect_finite(linear);
  expect_finite(full);
  EXPECT_TRUE(linear.result.status.ok()) << linear.result.status.message();
  EXPECT_TRUE(auto_run.status.ok()) << auto_run.status.message();
  EXPECT_EQ(linear.result.summary.fidelity.contact_law, "linear-hertz");
  EXPECT_EQ(linear.codes, (std::set<std::string>{"wheel_values_dt", "linear_hertz_unloaded"})) << codes_text(linear);
  for (const RunWarning& w : linear.result.summary.warnings)
    EXPECT_NE(w.message.find("unilateral linear Hertz on rung interaction/fe (pinned in the scene)"), std::string::npos)
        << w.message;
  EXPECT_TRUE(planner.codes.empty()) << codes_text(planner);
  EXPECT_EQ(auto_run.summary.fidelity.contact_law, "hertz");
  EXPECT_DOUBLE_EQ(auto_run.summary.dt_s, 1.25e-4);
  const double q_full = full.result.summary.min_contact_force_N;
  ASSERT_GT(q_full, 0.0);
  const double e_linear = linear.result.summary.min_contact_force_N / q_full - 1.0;
  const double e_planner = auto_run.summary.min_contact_force_N / q_full - 1.0;
  EXPECT_GT(e_linear, 0.01);               // why it warns: measured +2.54 %
  EXPECT_LE(std::abs(e_planner), 0.0039);  // measured -0.13 % (3x)
  table_row("pinned unilateral linear Hertz, German high, 400 km/h", linear,
            fmt::format("Q min vs Hertz dt/4: pinned {:+.3g} %, planner {:+.3g} %", 100 * e_linear, 100 * e_planner));
}

TEST(HardCases, TenMetreSpanAt500AtResonance) {
  // v = f0 d: 138.9 m/s over 25 m axle spacing, f0 = 5.56 Hz.
  const double f0 = 500 / 3.6 / 25.0, m = 10000, L = 10;
  const double EI = m * std::pow(2 * L * L * f0 / M_PI, 2);
  const json doc = moving_force_scene(L, EI, m, 0.01, 500, 5e-4, 10, 25.0);
  claimed("10 m span, 500 km/h, resonance (moving forces)", doc, with_dt(doc, 1.25e-4), ss_cutoff(f0), {}, 1e-10,
          {3.8e-4, 0.013, 0.0, 0.0}, "dt/4");  // measured w 0.0129 %, a_filt 0.45 %
}

TEST(HardCases, VeryLightBridgeAtResonanceHalfPercentDamping) {
  const double f0 = 5.0, m = 3000, L = 15;
  const double EI = m * std::pow(2 * L * L * f0 / M_PI, 2);
  const json doc = moving_force_scene(L, EI, m, 0.005, 360, 5e-4, 10, 20.0);  // v = f0 x 20 m
  claimed("light 15 m span (3 t/m), 0.5 %, resonance", doc, with_dt(doc, 1.25e-4), ss_cutoff(f0), {}, 1e-10, {2e-4, 0.014, 0.0, 0.0},
          "dt/4");  // measured w 0.00667 %, a_filt 0.479 %
}

TEST(HardCases, ZeroDampingAlphaZeroConservesEnergyInFreeVibration) {
  json doc = moving_force_scene(15, 1.5e10, 15000, 0.0, 200, 5e-4, 1, 0.0);
  doc["analysis"]["hht_alpha"] = 0.0;
  doc["analysis"]["free_vibration_s"] = 5.0;
  const Outcome o = run(doc, 30.0);
  expect_finite(o);
  EXPECT_TRUE(o.result.status.ok());
  EXPECT_TRUE(o.codes.empty()) << codes_text(o);
  // The trapezoidal rule conserves T + U exactly: the balance closes to
  // round-off (measured 1e-13 .. 1e-12).
  EXPECT_LE(o.result.summary.energy_residual, 1e-10);
  // Free vibration after the force has left: the amplitude of the first
  // second equals that of the last (no numerical damping).
  const auto& t = o.result.histories.t_s;
  const auto& u = o.result.histories.deck_displacement_m[0];
  const double t_end = t.back();
  double first = 0, last = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] > t_end - 5.0 + 0.5 && t[k] < t_end - 3.5) first = railvsi::testing::worst_of(first, std::abs(u[k]));
    if (t[k] > t_end - 1.0) last = railvsi::testing::worst_of(last, std::abs(u[k]));
  }
  EXPECT_GT(first, 0.0);
  // Measured 1.0019: the window maxima of a multi-mode response beat; the
  // energy balance above is the exact check.
  EXPECT_NEAR(last / first, 1.0, 5e-3);
  table_row("zero damping, alpha = 0, 5 s free vibration", o, fmt::format("amplitude ratio {:.5f}", last / first));
}

TEST(HardCases, StiffHertzWithCoarseDtWarns) {
  json doc = two_span_scene(300, 1e-3);
  // G of a 0.46 m wheel is 3.86e-8 R^-0.115; /100 makes k_H 1000x stiffer.
  doc["analysis"]["contact"]["G_m_per_N23"] = 3.86e-8 * std::pow(0.46, -0.115) / 100.0;
  const Outcome o = run(doc, kTwoSpanCutoff);
  expect_finite(o);
  // The row of docs/verification.md in full: unstable, these two warnings.
  EXPECT_EQ(o.result.status.code(), StatusCode::kUnstable) << o.result.status.message();
  EXPECT_EQ(o.codes, (std::set<std::string>{"contact_chatter", "dt_above_policy"})) << codes_text(o);
  table_row("Hertz 1000x stiffer, dt = 1 ms", o, "not claimed (dt above policy)");
}

TEST(HardCases, ContinuousFourSpanGirder) {
  json doc = with_irregularity(two_span_scene(300, 2.5e-4), {{"spectrum", "german-low"}, {"seed", 2}});
  doc["structure"]["spans_m"] = {15.0, 20.0, 20.0, 15.0};
  doc["structure"]["continuous"] = true;
  doc["outputs"]["points"] = {{{"name", "mid2"}, {"x_m", 25.0}}, {{"name", "mid3"}, {"x_m", 45.0}}};
  // f_cut: the third bending mode of a 15 m span of this deck alone is 9 x 6.2 = 56 Hz, of a 20 m span
  // 9 x 3.5 = 32 Hz; the continuous girder's lie between: 50 Hz is used (f_cut only selects the filter).
  claimed("continuous girder 15+20+20+15 m, German low", doc, with_dt(doc, 1.25e-4), 50.0, {}, 1e-9, {2.4e-5, 1.1e-3, 8e-3, 9e-5},
          "dt/2");  // measured w 0.000826 %, a_filt 0.039 %, dQ/Q 0.268 %, body 0.00306 %
}

void library_train_over_two_spans(const char* train, const Tolerances& tol, const std::set<std::string>& warnings) {
  json doc = with_irregularity(two_span_scene(300, 2.5e-4), {{"spectrum", "german-low"}, {"seed", 1}});
  doc["structure"]["track"].erase("approach_m");  // the whole train on the track at t = 0
  doc["train"] = train;
  claimed(fmt::format("{}, German low, 300 km/h", train), doc, with_dt(doc, 1.25e-4), kTwoSpanCutoff, warnings, 1e-9,
          tol, "dt/2");
}

// Measured 2026-11-27: Eurostar w 7.63e-5 %, a_filt 0.015 %, dQ/Q 1.17 %,
// body 4.64e-5 %; KHST w 0.00083 %, a_filt 0.0147 %, dQ/Q 0.95 %, body 0.000502 %.
// Both unload a wheel below 70 % of its load on the rail at the policy's
// 0.25 ms: wheel_values_dt (their dQ/Q moves about 1 % to dt/2).
TEST(HardCases, EurostarOverTwoSpans) {
  library_train_over_two_spans("Eurostar", {2.2e-6, 4.5e-4, 0.035, 1.3e-6}, {"wheel_values_dt"});
}
TEST(HardCases, KhstOverTwoSpans) {
  library_train_over_two_spans("KHST", {2.4e-5, 4.4e-4, 0.028, 1.5e-5}, {"wheel_values_dt"});
}

TEST(HardCases, ThreeDimensionalDeckAtFiveThousandDofs) {
  // One 25 m span of the deck-3d generator (hexahedra, two rails on pads),
  // about 5,000 DOFs; four 170 kN axles at 300 km/h shared by both rails.
  Deck3dOptions o;
  o.spans_m = {25.0};
  o.target_dofs = 5000;
  o.approach_m = 20.0;
  o.exit_m = 20.0;
  Scene scene;
  scene.structure = make_deck_3d(o).model;
  for (int i = 0; i < 4; ++i) scene.train.moving_forces.push_back({i * 3.0, 170e3});
  scene.speed_mps = 300 / 3.6;
  scene.analysis.dt_s = 5e-4;
  scene.analysis.contact.rail_lines = {0, 1};
  const double cutoff = ss_cutoff(4.3);  // f0 of the generator's default section at 25 m
  const auto run_at = [&](double dt) {
    Scene s = scene;
    s.analysis.dt_s = dt;
    return run(s, cutoff);
  };
  const Outcome coarse = run_at(5e-4), fine = run_at(2.5e-4);
  EXPECT_NEAR(scene.structure->num_dofs(), 5000, 250);
  expect_finite(coarse);
  EXPECT_TRUE(coarse.result.status.ok()) << coarse.result.status.message();
  EXPECT_TRUE(coarse.codes.empty()) << codes_text(coarse);
  EXPECT_LE(coarse.result.summary.energy_residual, 1e-10);
  const Convergence c = compare(coarse, fine);
  EXPECT_LE(c.displacement, 1.5e-6);  // measured 5.3e-7 (2026-11-27)
  EXPECT_LE(c.acceleration, 4.5e-4);  // measured 1.57e-4
  table_row(fmt::format("3D deck, 25 m, {} DOFs, 4 axles at 300 km/h", scene.structure->num_dofs()), coarse,
            convergence_text(c, "dt/2"));
}

TEST(HardCases, RailEndEntryInsideTheWindowWarns) {
  json doc = two_span_scene(300, 2.5e-4);
  doc["structure"]["track"]["approach_m"] = 5.0;
  const Outcome o = run(doc, kTwoSpanCutoff);
  expect_finite(o);
  EXPECT_TRUE(o.result.status.ok());
  // The entry transient unloads a wheel below 70 % on the rail: wheel_values_dt too.
  EXPECT_EQ(o.codes, (std::set<std::string>{"entry_inside_window", "wheel_values_dt"})) << codes_text(o);
  table_row("rail-end entry 5 m before the bridge", o, "not claimed (entry transient)");
}

TEST(HardCases, TimeStepOfTwentyMillisecondsWarnsAndHasNoFilteredValue) {
  const Outcome o = run(two_span_scene(300, 0.02), kTwoSpanCutoff);
  expect_finite(o);
  EXPECT_TRUE(o.result.status.ok()) << o.result.status.message();
  EXPECT_EQ(o.codes, (std::set<std::string>{"dt_above_policy", "filter_above_nyquist"})) << codes_text(o);
  EXPECT_FALSE(o.env.max_abs_acceleration_mps2.has_value());
  for (const PointEnvelope& p : o.env.points) EXPECT_FALSE(p.max_abs_acceleration_mps2.has_value());
  table_row("dt = 0.02 s", o, "not claimed (no filtered value)");
}

TEST(HardCases, BilateralLinearHertzOverTheDipFlagsTensionNotLoss) {
  json doc = with_irregularity(two_span_scene(300, 2.5e-4), defect("dip", 10.0, 1.0, 0.020));
  doc["analysis"]["contact"] = {{"law", "linear-hertz"}, {"unilateral", false}};
  const Outcome o = run(doc, kTwoSpanCutoff);
  expect_finite(o);
  EXPECT_TRUE(o.result.status.ok()) << o.result.status.message();
  // At 0.25 ms the 20 mm x 1 m dip is above the track bound too.
  EXPECT_EQ(o.codes, (std::set<std::string>{"dt_above_policy", "linear_hertz_unloaded", "tensile_contact"}))
      << codes_text(o);
  EXPECT_DOUBLE_EQ(o.result.summary.contact_loss_s, 0.0);
  EXPECT_GT(o.result.summary.max_unloading_ratio, 1.0);  // the model's tension, flagged
  table_row("bilateral linear Hertz over the 20 mm dip", o, "not claimed (tension)");
}


// The issue-33 scenes: sharp defects where the time-step policy used to
// accept 0.25 ms with "ok" and no warning. The policy now bounds dt by the
// profile's shortest feature (results/planning/time_step_policy.hpp, bound
// 4): at 0.25 ms each run warns dt_above_policy naming the factor and the
// feature; at the policy's step the dips converge.
void warns_at_quarter_millisecond(const std::string& name, const json& doc, const char* feature_text,
                                  double factor_min, double cutoff_hz = kTwoSpanCutoff) {
  const Outcome o = run(doc, cutoff_hz);
  expect_finite(o);
  EXPECT_TRUE(o.result.status.ok()) << o.result.status.message();
  EXPECT_EQ(o.codes, (std::set<std::string>{"dt_above_policy"})) << codes_text(o);
  bool named = false;
  for (const RunWarning& w : o.result.summary.warnings) {
    if (w.code != "dt_above_policy") continue;
    named = w.message.find("track profile") != std::string::npos && w.message.find(feature_text) != std::string::npos;
    EXPECT_TRUE(named) << w.message;
    ASSERT_TRUE(w.factor.has_value());
    EXPECT_GE(*w.factor, factor_min) << w.message;
  }
  EXPECT_TRUE(named);
  table_row(name, o, "not claimed (dt above the track bound)");
}

json dip_doc(double speed_kmh, double length_m, double depth_m, double dt_s) {
  return with_irregularity(two_span_scene(speed_kmh, dt_s), defect("dip", 10.0, length_m, depth_m));
}

TEST(HardCasesTrack, Dip30mmOverHalfMetreAt400WarnsAtQuarterMillisecond) {
  // Policy: 0.5 m / (150 x 111.1 m/s) = 3.0e-5 s, 0.25 ms is 8.3x that.
  warns_at_quarter_millisecond("dip 30 mm x 0.5 m, 400 km/h, 0.25 ms", dip_doc(400, 0.5, 0.030, 2.5e-4),
                               "30 mm peak to peak", 8.0);
}

TEST(HardCasesTrack, Dip30mmOverOneMetreAt350WarnsAtQuarterMillisecond) {
  // Policy: 1 m / (150 x 97.2 m/s) = 6.9e-5 s, 0.25 ms is 3.6x that.
  warns_at_quarter_millisecond("dip 30 mm x 1 m, 350 km/h, 0.25 ms", dip_doc(350, 1.0, 0.030, 2.5e-4),
                               "30 mm peak to peak", 3.5);
}

// Issue 33: the planner's contact-loss time over this dip was +2.25 % off
// the full model when the policy's step was 0.25 ms (its escalation ran at
// 0.125 ms: 37.375 against 36.547 ms at 15.6 us, measured again
// 2026-11-27). The track-aware policy gives 62.5 us; the planner ("auto":
// linear Hertz, repeated with unilateral Hertz at half that step) against
// the full model (unilateral Hertz at the policy's step / 4), both at the
// policy's step as a study plans it.
TEST(HardCasesTrack, PlannerContactLossTimeOverThe30mmDipWithinOnePercent) {
  const json doc = dip_doc(350, 1.0, 0.030, 2.5e-4);
  Scene scene = parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs", "hard case");
  const DeckFrequencies f = deck_frequencies(*scene.structure);
  const TimeStepChoice policy = choose_time_step(*scene.structure, scene.train, scene.speed_mps, scene.analysis.contact,
                                                 f.f0_hz, f.f3_hz, {}, scene.irregularity.get());
  EXPECT_DOUBLE_EQ(policy.dt_s, 6.25e-5) << policy.reason;
  json automatic = with_dt(doc, policy.dt_s);
  automatic["fidelity"] = "auto";
  const Outcome p = planned(automatic, kTwoSpanCutoff);
  const Result& planner = p.result;
  const Outcome full = run(with_dt(doc, policy.dt_s / 4), kTwoSpanCutoff);
  expect_finite(p);
  expect_finite(full);
  EXPECT_TRUE(planner.status.ok()) << planner.status.message();
  EXPECT_TRUE(p.codes.empty()) << codes_text(p);
  EXPECT_EQ(planner.summary.fidelity.contact_law, "hertz");  // escalated: the wheel leaves the rail
  EXPECT_DOUBLE_EQ(planner.summary.dt_s, policy.dt_s / 2);
  ASSERT_GT(full.result.summary.contact_loss_s, 0.0);
  const double loss = planner.summary.contact_loss_s / full.result.summary.contact_loss_s - 1.0;
  const double acc = rel(p.env.max_abs_acceleration_mps2, full.env.max_abs_acceleration_mps2);
  // Measured 2026-11-27: loss -0.043 % (36.53125 against 36.546875 ms; one
  // step of 31.25 us is 0.086 %), filtered deck acceleration +0.079 %.
  EXPECT_LE(std::abs(loss), 1.3e-3);
  EXPECT_LE(acc, 2.4e-3);
  table_row("planner over the dip 30 mm x 1 m, 350 km/h (policy 62.5 us, Hertz at 31.25 us)", p,
            fmt::format("vs Hertz at 15.6 us: contact loss {:+.3g} %, a_filt {:.3g} %", 100 * loss, 100 * acc));
}

TEST(HardCasesTrack, TenMillimetreStepDownThenUpWarns) {
  const json profile = {{"x_m", {-400.0, 10.0, 10.01, 12.0, 12.01, 400.0}},
                        {"r_m", {0.0, 0.0, -0.010, -0.010, 0.0, 0.0}}};
  // Each step rises over 0.01 m: lambda = 4.44 x 0.01 m, 150 steps at
  // 83.3 m/s need 3.6e-6 s; 0.25 ms is 70x that.
  warns_at_quarter_millisecond("10 mm step down, up 2 m later, 300 km/h, 0.25 ms",
                               with_irregularity(two_span_scene(300, 2.5e-4), profile), "10 mm peak to peak", 60.0);
}

TEST(HardCasesTrack, FiveMillimetreStepOverOneMillimetreWarns) {
  const json profile = {{"x_m", {-400.0, 10.0, 10.001, 400.0}}, {"r_m", {0.0, 0.0, 0.005, 0.005}}};
  // lambda = 4.44 mm: 3.6e-7 s needed, 0.25 ms is 700x that.
  warns_at_quarter_millisecond("5 mm step over 1 mm, 300 km/h, 0.25 ms",
                               with_irregularity(two_span_scene(300, 2.5e-4), profile), "5 mm peak to peak", 600.0);
}

TEST(HardCasesTrack, ShortWavelengthProfileWarns) {
  // Corrugation-like: 0.5 mm amplitude, 0.3 m wavelength, 66 periods, 300
  // km/h: v^2 r'' = 83.3^2 x 0.0005 x (2 pi / 0.3)^2 = 1,520 m/s^2 lifts the
  // wheel: 0.3 m / (150 x 83.3 m/s) = 2.4e-5 s; 0.25 ms is 10.4x that.
  json x = json::array(), r = json::array();
  for (int i = -1; i <= 1981; ++i) {
    const double xi = 5.0 + 0.01 * i;
    x.push_back(xi);
    r.push_back(i >= 0 && i <= 1980 ? 0.0005 * std::sin(2.0 * M_PI * (xi - 5.0) / 0.3) : 0.0);
  }
  x.insert(x.begin(), -400.0);
  r.insert(r.begin(), 0.0);
  x.push_back(400.0);
  r.push_back(0.0);
  warns_at_quarter_millisecond("corrugation 0.5 mm x 0.3 m, 300 km/h, 0.25 ms",
                               with_irregularity(two_span_scene(300, 2.5e-4), {{"x_m", x}, {"r_m", r}}),
                               "mm peak to peak", 9.0);
}

// The viaduct scenes: three simply supported 25 m spans with
// ballasted track (jobs/examples/viaduct-ice3.json's structure), one ICE3
// coach (the whole train takes 4-5x longer: measured by hand, see
// docs/verification.md), Hertz, at the time-step policy's step for the
// scene as a study plans it, against a quarter of it.
json viaduct_scene(double speed_kmh, json irregularity) {
  json doc = {{"structure",
               {{"generator", "bridge-2d"},
                {"spans_m", {25.0, 25.0, 25.0}},
                {"deck", {{"EI_Nm2", 7.124e10}, {"mass_kg_per_m", 18000}}},
                {"damping", {{"ratio", 0.02}}},
                {"track", json::object()}}},
              {"train", one_coach()},
              {"speed_kmh", speed_kmh},
              {"irregularity", std::move(irregularity)},
              {"analysis", {{"dt_s", 2.5e-4}, {"hht_alpha", -0.05}, {"contact", {{"law", "hertz"}}}}}};
  const Scene scene = parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs", "hard case");
  const DeckFrequencies f = deck_frequencies(*scene.structure);
  const TimeStepChoice policy = choose_time_step(*scene.structure, scene.train, scene.speed_mps,
                                                 scene.analysis.contact, f.f0_hz, f.f3_hz, {}, scene.irregularity.get());
  doc["analysis"]["dt_s"] = policy.dt_s;
  return doc;
}

// f0 = 5.0 Hz, f3 = 45 Hz for these spans (the example's EI).
const double kViaductCutoff = ss_cutoff(5.0);

json viaduct_dip(double speed_kmh) {
  return viaduct_scene(speed_kmh, {{"defects", {{{"type", "dip"}, {"x_m", 37.0}, {"length_m", 1.0}, {"depth_m", 0.03}}}}});
}

TEST(HardCasesViaduct, TenMillimetreStepDownThenUpAt300WarnsAtThePolicysFloor) {
  const json doc = viaduct_scene(300, {{"x_m", {-400.0, 37.0, 37.01, 39.0, 39.01, 400.0}},
                                       {"r_m", {0.0, 0.0, -0.010, -0.010, 0.0, 0.0}}});
  EXPECT_DOUBLE_EQ(doc["analysis"]["dt_s"].get<double>(), 2e-3 / 128);  // the ladder's floor
  // A step's rise over 0.01 m needs 3.6 us at 83.3 m/s: the floor is 4.4x
  // that. 36 s on a loaded machine (the floor's 200,000 steps).
  warns_at_quarter_millisecond("viaduct, 10 mm step down, up 2 m later, 300 km/h, one coach, 15.6 us", doc,
                               "10 mm peak to peak", 4.0, kViaductCutoff);
}

// The policy's step against a quarter of it: deck displacement, filtered
// deck acceleration, car body and the contact-loss time (the wheel leaves
// the rail after the dip: Q min 0 and dQ/Q 1 in both).
struct DipConvergence {
  double w, a, body, loss;
};
DipConvergence viaduct_dip_converges(const char* name, double speed_kmh, double policy_dt_s) {
  const json doc = viaduct_dip(speed_kmh);
  EXPECT_DOUBLE_EQ(doc["analysis"]["dt_s"].get<double>(), policy_dt_s);
  const Outcome coarse = run(doc, kViaductCutoff);
  const Outcome fine = run(with_dt(doc, policy_dt_s / 4), kViaductCutoff);
  expect_finite(coarse);
  expect_finite(fine);
  EXPECT_TRUE(coarse.result.status.ok()) << coarse.result.status.message();
  EXPECT_TRUE(fine.result.status.ok()) << fine.result.status.message();
  EXPECT_TRUE(coarse.codes.empty()) << codes_text(coarse);
  EXPECT_LE(coarse.result.summary.energy_residual, 1e-9);
  EXPECT_GT(fine.result.summary.contact_loss_s, 0.0);
  EXPECT_DOUBLE_EQ(coarse.result.summary.max_unloading_ratio, 1.0);
  const Convergence c = compare(coarse, fine);
  const double loss = rel(coarse.result.summary.contact_loss_s, fine.result.summary.contact_loss_s);
  table_row(name, coarse,
            fmt::format("{}, contact loss {:.3g} %", convergence_text(c, "dt/4"), 100 * loss));
  return {c.displacement, c.acceleration, c.carbody, loss};
}

TEST(HardCasesViaduct, Dip30mmOverOneMetreAt350ConvergesAtThePolicysStep) {
  // 1 m / (150 x 97.2 m/s) = 6.9e-5 s -> 62.5 us.
  const DipConvergence c = viaduct_dip_converges("viaduct, dip 30 mm x 1 m, 350 km/h, one coach", 350, 6.25e-5);
  // Measured 2026-11-27 (26 s for both runs on a loaded machine): w
  // 7.7e-6, a_filt 1.04e-5, body 4.3e-4, contact loss 1.0e-3; 3x each.
  EXPECT_LE(c.w, 2.3e-5);
  EXPECT_LE(c.a, 3.1e-5);
  EXPECT_LE(c.body, 1.3e-3);
  EXPECT_LE(c.loss, 3.0e-3);
}

TEST(HardCasesViaduct, Dip30mmOverOneMetreAt400ConvergesAtThePolicysStep) {
  // 1 m / (150 x 111.1 m/s) = 6.0e-5 s -> 31.25 us.
  const DipConvergence c = viaduct_dip_converges("viaduct, dip 30 mm x 1 m, 400 km/h, one coach", 400, 3.125e-5);
  // Measured 2026-11-27 (30 s): w 2.1e-5, a_filt 3.8e-4, body 1.0e-4,
  // contact loss 6.0e-3 (steps of 31.25 us in a 20 ms loss); 3x each, the
  // loss held to the 1 % the issue asks.
  EXPECT_LE(c.w, 6.3e-5);
  EXPECT_LE(c.a, 1.1e-3);
  EXPECT_LE(c.body, 3.1e-4);
  EXPECT_LE(c.loss, 0.01);
}

}  // namespace
}  // namespace railvsi

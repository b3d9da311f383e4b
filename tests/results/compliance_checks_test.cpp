// The code formulas and verdict rules of the compliance report against hand
// calculations (values worked out here with a calculator, not by the code).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "compliance/check_verdict.hpp"
#include "compliance/code_values.hpp"
#include "envelopes/speed_envelope.hpp"
#include "report/line_plot.hpp"

namespace railvsi {
namespace {

TEST(CodeValues, DynamicFactorsMatchHandCalculation) {
  // L = 20 m: sqrt(20) - 0.2 = 4.272136; Phi3 = 2.16/4.272136 + 0.73 = 1.2356019,
  // Phi2 = 1.44/4.272136 + 0.82 = 1.1570679.
  EXPECT_NEAR(dynamic_factor_phi3(20.0), 1.2356019, 1e-7);
  EXPECT_NEAR(dynamic_factor_phi2(20.0), 1.1570679, 1e-7);
  // L = 4 m: 2.16/1.8 + 0.73 = 1.93 (inside the range).
  EXPECT_NEAR(dynamic_factor_phi3(4.0), 1.93, 1e-12);
  // Clamped: L = 3 m gives 2.14 > 2.00; L = 100 m gives Phi2 = 0.9669 < 1.00.
  EXPECT_EQ(dynamic_factor_phi3(3.0), 2.0);
  EXPECT_EQ(dynamic_factor_phi2(100.0), 1.0);
  EXPECT_EQ(dynamic_factor_phi2(1.0), 1.67);
}

TEST(CodeValues, DeterminantLengthOfSimpleAndContinuousGirders) {
  EXPECT_EQ(determinant_length_m({25.0}, false), 25.0);
  EXPECT_EQ(determinant_length_m({20.0, 30.0}, false), 30.0);
  // Continuous, 3 spans 20 + 30 + 20: 1.3 x 23.333 = 30.333 > 30.
  EXPECT_NEAR(determinant_length_m({20.0, 30.0, 20.0}, true), 1.3 * 70.0 / 3.0, 1e-12);
  // Continuous, 2 spans 10 + 40: 1.2 x 25 = 30 < 40, so the longest span.
  EXPECT_EQ(determinant_length_m({10.0, 40.0}, true), 40.0);
}

TEST(CodeValues, PhiDoublePrimeMatchesHandCalculation) {
  // L = 20 m, n0 = 5 Hz, v = 300 km/h (a = 1): 56 e^-4 = 1.025675,
  // 50 (5*20/80 - 1) e^-1 = 4.598493, sum / 100 = 0.05624168.
  EXPECT_NEAR(phi_double_prime(20.0, 5.0, 300.0 / 3.6), 0.05624168, 1e-7);
  // v = 11 m/s: a = 0.5, half the value.
  EXPECT_NEAR(phi_double_prime(20.0, 5.0, 11.0), 0.5 * 0.05624168, 1e-7);
  // Never negative: L = 40 m, n0 = 1 Hz: 56 e^-16 + 50 (-0.5) e^-4 < 0.
  EXPECT_EQ(phi_double_prime(40.0, 1.0, 50.0), 0.0);
}

TEST(CodeValues, LimitsOfTheAnnexA2) {
  EXPECT_EQ(deck_acceleration_limit_ballasted_mps2().value, 3.5);
  EXPECT_EQ(deck_acceleration_limit_direct_fastening_mps2().value, 5.0);
  EXPECT_EQ(deflection_span_ratio().value, 600.0);
  ASSERT_EQ(comfort_levels().size(), 3u);
  EXPECT_EQ(comfort_levels()[0].b_v_mps2, 1.0);
  EXPECT_EQ(comfort_levels()[1].b_v_mps2, 1.3);
  EXPECT_EQ(comfort_levels()[2].b_v_mps2, 2.0);
  EXPECT_EQ(twist_limit_mm_per_3m(100).value, 4.5);
  EXPECT_EQ(twist_limit_mm_per_3m(160).value, 3.0);
  EXPECT_EQ(twist_limit_mm_per_3m(300).value, 1.5);
  // The values not read in the standard's text say so.
  EXPECT_FALSE(deflection_span_ratio().verified);
  EXPECT_FALSE(unloading_ratio_limit().verified);
}

CheckResult limit(double value) {
  CheckResult c;
  c.limit = value;
  return c;
}

TEST(CheckVerdict, PassOnlyWhenEveryCaseHasAValueWithinTheLimit) {
  const auto r = evaluate_upper_limit(limit(3.5), {{"A", 100, "none", 1.0}, {"A", 200, "none", 3.4}});
  EXPECT_EQ(r.verdict, Verdict::kPass);
  ASSERT_TRUE(r.governing);
  EXPECT_EQ(r.governing->speed_kmh, 200);
  EXPECT_EQ(r.cases, 2);
  EXPECT_EQ(r.missing, 0);
}

TEST(CheckVerdict, IncompleteWhenACaseHasNoValue) {
  const auto r = evaluate_upper_limit(limit(3.5), {{"A", 100, "none", 1.0}, {"A", 200, "none", std::nullopt}});
  EXPECT_EQ(r.verdict, Verdict::kIncomplete);
  EXPECT_EQ(r.missing, 1);
  EXPECT_EQ(evaluate_upper_limit(limit(3.5), {}).verdict, Verdict::kIncomplete);
}

TEST(CheckVerdict, FailWhenAnyCaseExceedsEvenWithMissingCases) {
  const auto r = evaluate_upper_limit(limit(3.5), {{"A", 100, "none", 3.6}, {"A", 200, "none", std::nullopt}});
  EXPECT_EQ(r.verdict, Verdict::kFail);
  EXPECT_EQ(r.governing->value, 3.6);
}

TEST(CheckVerdict, EqualValuesGoToTheCaseTheEnvelopeOverSpeedsNames) {
  // A moving-force job gives the same value with and without a profile: the
  // check names the case the envelope over speeds names (lowest speed, then
  // profile label), whatever the order of the cases.
  const std::vector<CheckCase> cases = {{"A", 340, "none", 34.68, "n"},
                                        {"A", 340, "german-low seed 1", 34.68, "g"},
                                        {"A", 350, "german-low seed 1", 34.68, "h"}};
  std::vector<CaseValue> rows;
  for (const CheckCase& c : cases) rows.push_back({c.train, c.speed_kmh, c.irregularity, c.value, c.variant});
  const TrainEnvelope e = envelope_over_speeds(rows, Extreme::kMax).at(0);
  for (const auto& order : {cases, std::vector<CheckCase>(cases.rbegin(), cases.rend())}) {
    const auto r = evaluate_upper_limit(limit(35.0), order);
    ASSERT_TRUE(r.governing);
    EXPECT_EQ(r.governing->irregularity, e.governing_irregularity);
    EXPECT_EQ(r.governing->speed_kmh, e.governing_speed_kmh);
    EXPECT_EQ(r.governing->job_id, "g");
  }
}

TEST(CheckVerdict, PerTrainVerdictsFollowTheSameRules) {
  const auto r = evaluate_upper_limit(limit(3.5), {{"A", 100, "none", 3.6, "a1"},
                                                   {"B", 100, "none", 1.0, "b1"},
                                                   {"A", 200, "none", std::nullopt, "a2"},
                                                   {"B", 200, "none", std::nullopt, "b2"},
                                                   {"C", 100, "none", 2.0, "c1"}});
  EXPECT_EQ(r.verdict, Verdict::kFail);
  const auto t = per_train(r);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].all_cases.front().train, "A");
  EXPECT_EQ(t[0].verdict, Verdict::kFail);  // an exceedance wins over the missing case
  EXPECT_EQ(t[0].governing->job_id, "a1");
  EXPECT_EQ(t[1].verdict, Verdict::kIncomplete);
  EXPECT_EQ(t[1].cases, 2);
  EXPECT_EQ(t[1].missing, 1);
  EXPECT_EQ(t[1].governing->value, 1.0);
  EXPECT_EQ(t[2].verdict, Verdict::kPass);
  EXPECT_TRUE(per_train(CheckResult{}).empty());
}

TEST(CheckVerdict, OverallVerdict) {
  CheckResult pass, fail, incomplete, skipped;
  pass.verdict = Verdict::kPass;
  fail.verdict = Verdict::kFail;
  incomplete.verdict = Verdict::kIncomplete;
  skipped.verdict = Verdict::kNotEvaluated;
  EXPECT_EQ(overall_verdict({pass, skipped}), Verdict::kPass);
  EXPECT_EQ(overall_verdict({pass, incomplete}), Verdict::kIncomplete);
  EXPECT_EQ(overall_verdict({incomplete, fail}), Verdict::kFail);
  EXPECT_EQ(overall_verdict({skipped}), Verdict::kNotEvaluated);
}

TEST(LinePlot, NiceTicksAreRoundAndCoverTheRange) {
  // 320 / 6 = 53.3 per tick: the next of 1, 2, 5 x 10^k is 100.
  EXPECT_EQ(nice_ticks(100, 420), (std::vector<double>{100, 200, 300, 400}));
  // 0.0137 / 6 = 0.00228: the next is 0.005.
  const auto s = nice_ticks(0.0, 0.0137);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_NEAR(s[1] - s[0], 0.005, 1e-15);
  EXPECT_EQ(s.front(), 0.0);
}

TEST(LinePlot, TextIsEscaped) {
  EXPECT_EQ(html_escape("<b>&\"x'\x1b[31m"), "&lt;b&gt;&amp;&quot;x&#39;[31m");
  LinePlot p;
  p.title = "<script>";
  p.series.push_back({"A&B", {{0, 1}, {1, 2}}});
  const std::string svg = render_svg(p);
  EXPECT_EQ(svg.find("<script>"), std::string::npos);
  EXPECT_NE(svg.find("A&amp;B"), std::string::npos);
  EXPECT_NE(svg.find("<path class=\"series\""), std::string::npos);
}

}  // namespace
}  // namespace railvsi

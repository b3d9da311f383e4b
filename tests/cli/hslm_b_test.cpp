// HSLM-B (EN 1991-2 6.4.6.1.1, Figure 6.13): N point forces of 170 kN at a
// uniform spacing d, for simply supported spans L < 7 m. N and d are given
// (EN 1991-2 reads them from L in Figure 6.14, whose values are not built
// in); the layouts below are computed by hand from that rule, not by the
// code under test.
#include <algorithm>
#include <cmath>

#include "core/input_error.hpp"
#include "io/train_loader.hpp"
#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

Train hslm_b(const json& h) { return parse_train({{"name", "B"}, {"hslm_b", h}}); }

std::string error_path(const json& h) {
  try {
    hslm_b(h);
  } catch (const InputError& e) {
    return e.json_path();
  }
  return "accepted";
}

TEST(HslmB, AxlesAreNForcesOf170kNAtUniformSpacing) {
  // (N, d) pairs of the kind Figure 6.14 gives (N between 10 and 20, d
  // between 2.5 and 3.5 m are the ranges quoted for the figure; the pairs
  // are examples, not read from it). Offsets k d, k = 0..N-1; the length
  // from the first to the last force (N - 1) d, by hand: 10 x 3.5 -> 31.5 m,
  // 20 x 2.5 -> 47.5 m, 15 x 3 -> 42 m.
  const struct {
    int N;
    double d, length_m;
  } cases[] = {{10, 3.5, 31.5}, {20, 2.5, 47.5}, {15, 3.0, 42.0}};
  for (const auto& c : cases) {
    const Train t = hslm_b({{"point_forces", c.N}, {"spacing_m", c.d}, {"span_m", 5.0}});
    ASSERT_EQ(t.moving_forces.size(), static_cast<std::size_t>(c.N));
    EXPECT_TRUE(t.is_moving_forces());
    EXPECT_DOUBLE_EQ(t.length_m(), c.length_m);
    EXPECT_DOUBLE_EQ(t.coach_length_m, c.d) << "the regular spacing d is the resonance length";
    for (int k = 0; k < c.N; ++k) {
      EXPECT_DOUBLE_EQ(t.moving_forces[static_cast<std::size_t>(k)].offset_m, k * c.d);
      EXPECT_EQ(t.moving_forces[static_cast<std::size_t>(k)].load_N, 170000.0);  // EN 1991-2 6.4.6.1.1: 170 kN
    }
  }
}

TEST(HslmB, SpanOfSevenMetresOrMoreAndMissingNOrDAreRefusedAtTheirPaths) {
  EXPECT_EQ(error_path({{"point_forces", 10}, {"spacing_m", 3.5}, {"span_m", 7.0}}), "/hslm_b/span_m");
  // The figure is not built in: a span alone does not give N and d.
  EXPECT_EQ(error_path({{"span_m", 5.0}}), "/hslm_b");
  EXPECT_EQ(error_path({{"point_forces", 10}}), "/hslm_b");
  EXPECT_EQ(error_path({{"point_forces", 10}, {"spacing_m", 0.0}}), "/hslm_b/spacing_m");
}

class HslmBScene : public VsiCliTest {};

// Midspan deflection of a simply supported span L under loads P at x_k
// (0 <= x_k <= L), by hand: P b (3 L^2 - 4 b^2) / (48 EI), b = min(x, L - x).
double static_midspan_deflection_m(const std::vector<double>& x_m, double P, double L, double EI) {
  double w = 0.0;
  for (double x : x_m)
    if (x >= 0.0 && x <= L) {
      const double b = std::min(x, L - x);
      w += P * b * (3.0 * L * L - 4.0 * b * b) / (48.0 * EI);
    }
  return w;
}

TEST_F(HslmBScene, RunsOnAFiveMetreSpanAndMatchesTheStaticDeflectionAtLowSpeed) {
  // f0 = pi / (2 L^2) sqrt(EI / m) = 28.1 Hz; at 5 km/h the speed parameter
  // v / (2 f0 L) is 5e-3, so the response is quasi-static.
  const double L = 5.0, EI = 2.0e9, m = 10000.0, P = 170000.0, d = 2.5;
  const int N = 20;
  const json scene = {
      {"structure",
       {{"generator", "bridge-2d"},
        {"spans_m", {L}},
        {"deck", {{"EI_Nm2", EI}, {"mass_kg_per_m", m}}},
        {"damping", {{"ratio", 0.02}}},
        {"element_length_m", 0.25},
        {"track", nullptr}}},
      {"train", {{"name", "HSLM-B"}, {"hslm_b", {{"point_forces", N}, {"spacing_m", d}, {"span_m", L}}}}},
      {"speed_kmh", 5.0},
      {"irregularity", nullptr},
      {"analysis", {{"dt_s", 2.0e-3}}},
      {"outputs", {{"points", json::array({{{"name", "mid"}, {"x_m", 2.5}}})}}}};
  const VsiRun run = vsi("simulate '" + write_json("b.json", scene).string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(run.out);
  ASSERT_EQ(summary["status"], "ok");
  const double dynamic_m = summary["deck"]["points"][0]["max_abs_displacement_m"].get<double>();

  // The largest static midspan deflection as the train passes: the first
  // force at s, the others at s - k d; s scanned in 1 mm steps.
  double static_m = 0.0;
  for (double s = 0.0; s <= L + (N - 1) * d; s += 1e-3) {
    std::vector<double> x;
    for (int k = 0; k < N; ++k) x.push_back(s - k * d);
    static_m = railvsi::testing::worst_of(static_m, static_midspan_deflection_m(x, P, L, EI));
  }
  // At d = 2.5 m two forces share the span: the largest is at 1.25 and
  // 3.75 m, 2 P b (3 L^2 - 4 b^2) / (48 EI) with b = 1.25 m = 0.304 mm, more
  // than one force at midspan (0.221 mm).
  std::printf("HSLM-B N=%d d=%g on L=%g m at 5 km/h: max midspan %.6e m, static %.6e m, ratio %.6f\n", N, d, L,
              dynamic_m, static_m, dynamic_m / static_m);
  // Measured 3.3e-4 (the dynamic part at this speed, and dt = 2 ms).
  EXPECT_NEAR(dynamic_m / static_m, 1.0, 1e-3);
}

}  // namespace
}  // namespace railvsi::test

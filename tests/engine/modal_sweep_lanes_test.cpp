// The exact modal sweep of moving forces run several speeds at once
// (ModalSweep::run_group, one lane per speed) and its tabulated train load:
// a group gives each run the bits it has alone, and the table gives the
// modal load of the axles summed one by one on the rail's shape functions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "analysis/modal_sweep.hpp"
#include "core/sampled_peak.hpp"
#include "generators/bridge_2d.hpp"
#include "generators/deck_3d.hpp"
#include "model/rail_line.hpp"
#include "simulation/modal_section_forces.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

std::shared_ptr<const StructureModel> span_15m() {
  Bridge2dOptions o;
  o.spans_m = {15.0};
  o.deck_first_frequency_hz = 5.0;
  o.deck_mass_kg_per_m = 15000.0;
  o.damping_ratio = 0.01;
  return make_bridge_2d(o);
}

// Bogies of two axles 3 m apart, 18 m apart, with a heavier first one.
Train coaches() {
  Train t;
  for (int c = 0; c < 5; ++c)
    for (double a : {0.0, 3.0}) t.moving_forces.push_back({18.0 * c + a, c == 0 ? 195e3 : 170e3});
  return t;
}

RunSummary sections_of(const ModalSweepRun& run, std::size_t points) {
  RunSummary s;
  s.points.resize(points);
  if (run.sections) run.sections->summarize(s);
  return s;
}

void expect_same_bits(const ModalSweepRun& grouped, const std::vector<std::vector<double>>& grouped_acc,
                      const ModalSweepRun& alone, const std::vector<std::vector<double>>& alone_acc, std::size_t points) {
  EXPECT_EQ(grouped.status.ok(), alone.status.ok());
  EXPECT_EQ(grouped.steps, alone.steps);
  EXPECT_EQ(grouped.max_abs_displacement_m, alone.max_abs_displacement_m);
  EXPECT_EQ(grouped.max_abs_acceleration_mps2, alone.max_abs_acceleration_mps2);
  EXPECT_EQ(grouped_acc, alone_acc);
  EXPECT_EQ(grouped.max_abs_twist_m, alone.max_abs_twist_m);
  EXPECT_EQ(grouped.twist_x_m, alone.twist_x_m);
  ASSERT_EQ(grouped.sections.has_value(), alone.sections.has_value());
  const RunSummary g = sections_of(grouped, points), a = sections_of(alone, points);
  for (std::size_t p = 0; p < points; ++p) {
    EXPECT_EQ(g.points[p].max_abs_bending_moment_Nm, a.points[p].max_abs_bending_moment_Nm);
    EXPECT_EQ(g.points[p].max_abs_shear_force_N, a.points[p].max_abs_shear_force_N);
  }
  ASSERT_EQ(g.supports.size(), a.supports.size());
  for (std::size_t s = 0; s < g.supports.size(); ++s) {
    EXPECT_EQ(g.supports[s].max_reaction_N, a.supports[s].max_reaction_N);
    EXPECT_EQ(g.supports[s].max_abs_rotation_rad, a.supports[s].max_abs_rotation_rad);
  }
}

// The deck's peaks, refined chunk by chunk while the run goes, are those
// of refining the run's kept samples at once (core/sampled_peak.hpp), to
// the bit.
void expect_peaks_of_whole_run(const ModalSweepRun& run, const ModalSweepWorkspace& ws, std::size_t lane) {
  const auto samples = static_cast<std::size_t>(run.steps) + 1;
  ASSERT_EQ(run.max_abs_displacement_m.size(), ws.displacement[lane].size());
  for (std::size_t i = 0; i < run.max_abs_displacement_m.size(); ++i) {
    EXPECT_EQ(run.max_abs_displacement_m[i], refined_max_abs(ws.displacement[lane][i].data(), samples));
    EXPECT_EQ(run.max_abs_acceleration_mps2[i], refined_max_abs(ws.acceleration[lane][i].data(), samples));
  }
}

// Runs `lanes` as one group (in the fastest and in the portable machine
// code) and one by one; every number must be the same bits.
void check_group(const ModalSweep& sweep, const std::vector<SweepLane>& lanes, std::size_t points) {
  for (const auto code : {LaneCode::kFastest, LaneCode::kPortable}) {
    SCOPED_TRACE(code == LaneCode::kFastest ? "fastest code" : "portable code");
    ModalSweepWorkspace group_ws, alone_ws;
    const std::vector<ModalSweepRun> grouped = sweep.run_group(lanes, group_ws, code);
    ASSERT_EQ(grouped.size(), lanes.size());
    for (std::size_t l = 0; l < lanes.size(); ++l) {
      SCOPED_TRACE("lane " + std::to_string(l));
      const ModalSweepRun alone = sweep.run(lanes[l].x0_m, lanes[l].speed_mps, lanes[l].n_steps, alone_ws);
      ASSERT_TRUE(alone.status.ok()) << alone.status.message();
      EXPECT_EQ(alone.steps, lanes[l].n_steps);
      expect_same_bits(grouped[l], group_ws.acceleration[l], alone, alone_ws.acceleration[0], points);
      expect_peaks_of_whole_run(alone, alone_ws, 0);
      expect_peaks_of_whole_run(grouped[l], group_ws, l);
    }
  }
}

TEST(ModalSweepLanes, SpeedsRunTogetherGiveTheBitsOfEachRunAlone) {
  const auto s = span_15m();
  ModalBasisOptions o;
  o.max_frequency_hz = 54.0;
  const ModalBasis basis(s, o);
  const auto sections = modal_section_forces(basis, {0});
  ASSERT_NE(sections, nullptr);
  const double dt = 9.66e-4;
  const ModalSweep sweep(basis, coaches(), {0}, dt, sections);
  // Each speed runs as long as the train needs to cross (different lengths
  // in one group), the slowest from a start on a node.
  const auto lane = [&](double speed_kmh, double x0_m) {
    const double v = speed_kmh / 3.6;
    return SweepLane{x0_m, v, static_cast<long>(std::ceil((15.0 + 75.0 + 5.0 - x0_m) / v / dt))};
  };
  check_group(sweep, {lane(100.0, 0.0), lane(163.3, -1.3), lane(250.0, -2.0), lane(400.0, 0.25)}, 1);
  // Three runs: the fourth lane idles.
  check_group(sweep, {lane(187.0, 0.0), lane(120.0, -0.4), lane(301.0, 0.0)}, 1);
  // A standing train (speed 0) beside moving ones.
  check_group(sweep, {lane(200.0, 0.0), SweepLane{7.5, 0.0, 300}}, 1);
}

TEST(ModalSweepLanes, TwoRailsAndTheDeckTwistGiveTheBitsOfEachRunAlone) {
  Deck3dOptions d;
  d.spans_m = {20.0};
  d.rail_y_m = {0.75, 2.25};
  d.approach_m = 6.0;
  d.exit_m = 6.0;
  d.sleeper_spacing_m = 0.5;
  d.mesh = Deck3dMesh{{20}, 6, 2};
  const Deck3d deck = make_deck_3d(d);
  ModalBasisOptions o;
  o.max_frequency_hz = 60.0;
  const ModalBasis basis(deck.model, o);
  Train t;
  t.moving_forces = {{0.0, 170e3}, {3.0, 170e3}, {17.5, 170e3}};
  const double dt = 1e-3;
  const ModalSweep sweep(basis, t, {0, 1}, dt);
  ASSERT_TRUE(sweep.twist_gauge().available());
  std::vector<SweepLane> lanes;
  for (double kmh : {150.0, 210.0, 280.0, 330.0}) lanes.push_back({0.0, kmh / 3.6, static_cast<long>(std::ceil(55.0 / (kmh / 3.6) / dt))});
  check_group(sweep, lanes, deck.model->outputs().size());
}

// The modal load from the train's table against the axles summed one by
// one (RailLine::locate and its Hermite weights on the mode shapes, written
// here apart from the sweep): at rest (speed 0, no step) the sweep's
// displacement at an output is sum_k phi_k p_k / omega_k^2.
TEST(ModalSweepLanes, TabulatedTrainLoadIsTheSumOverTheAxles) {
  const auto s = span_15m();
  ModalBasisOptions o;
  o.max_frequency_hz = 200.0;
  const ModalBasis basis(s, o);
  const Train train = coaches();
  const ModalSweep sweep(basis, train, {0}, 1e-3, nullptr, DeckOutputCorrection::kNone);
  const RailLine& rail = s->rails()[0];
  const int n = basis.num_modes();
  const auto independent = [&](double x) {
    std::vector<double> p(static_cast<std::size_t>(n), 0.0);
    for (const MovingForce& f : train.moving_forces) {
      const auto at = rail.locate(x - f.offset_m);
      if (!at) continue;
      for (int j = 0; j < 4; ++j) {
        if (at->dof[static_cast<std::size_t>(j)] < 0) continue;
        const double* phi = basis.row(at->dof[static_cast<std::size_t>(j)]);
        for (int k = 0; k < n; ++k) p[static_cast<std::size_t>(k)] -= f.load_N * at->weight[static_cast<std::size_t>(j)] * phi[k];
      }
    }
    double u = 0.0;
    for (int k = 0; k < n; ++k) {
      const double w = basis.omega_rad_s()[static_cast<std::size_t>(k)];
      u += basis.at_outputs()(0, k) * p[static_cast<std::size_t>(k)] / (w * w);
    }
    return std::abs(u);
  };
  // Positions inside pieces (random) and on breakpoints (an axle on a node
  // or a rail end).
  std::vector<double> xs;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> along(-1.0, 15.0 + 78.0);
  for (int i = 0; i < 300; ++i) xs.push_back(along(rng));
  for (double node : rail.x_m)
    for (const MovingForce& f : train.moving_forces) xs.push_back(node + f.offset_m);
  ModalSweepWorkspace ws;
  double worst = 0.0, peak = 0.0;
  for (double x : xs) {
    const ModalSweepRun run = sweep.run(x, 0.0, 0, ws);
    const double expected = independent(x);
    worst = railvsi::testing::worst_of(worst, std::abs(run.max_abs_displacement_m[0] - expected));
    peak = railvsi::testing::worst_of(peak, expected);
  }
  std::printf("[sweep] tabulated train load vs the axles one by one: %.2e of the peak %.3e m (%zu positions)\n",
              worst / peak, peak, xs.size());
  ASSERT_GT(peak, 1e-4);
  // Measured 3.9e-16 of the peak: round-off (the table's Taylor shift of each cubic).
  EXPECT_LT(worst, 1e-14 * peak);
}

// The static correction of the outputs (DeckOutputCorrection::kStatic)
// gives back what the modes left out: at rest, the midspan deflection of a
// simply supported beam under the train is the closed form
// P a (3L^2 - 4a^2) / (48 EI) per axle (a: its distance from the nearer
// support), whatever the modes kept; the modes alone miss a share of it.
TEST(ModalSweepLanes, StaticCorrectionGivesTheClosedFormStaticDeflectionWithOneMode) {
  Bridge2dOptions o;
  const double L = 15.0, EI = 7.0e10;
  o.spans_m = {L};
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = 15000.0;
  o.damping_ratio = 0.01;
  const auto s = make_bridge_2d(o);
  ModalBasisOptions bo;
  bo.max_frequency_hz = 20.0;  // the first bending mode (15.1 Hz) alone
  const ModalBasis basis(s, bo);
  ASSERT_EQ(basis.num_modes(), 1);
  ASSERT_EQ(s->outputs().size(), 1u);
  ASSERT_NEAR(s->outputs()[0].x_m, L / 2, 1e-12);
  const Train train = coaches();
  const ModalSweep corrected(basis, train, {0}, 1e-3);
  const ModalSweep modes_only(basis, train, {0}, 1e-3, nullptr, DeckOutputCorrection::kNone);
  const auto closed_form = [&](double x) {
    double u = 0.0;
    for (const MovingForce& f : train.moving_forces) {
      const double xa = x - f.offset_m;
      if (xa < 0.0 || xa > L) continue;
      const double a = std::min(xa, L - xa);
      u += f.load_N * a * (3 * L * L - 4 * a * a) / (48 * EI);
    }
    return u;
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> along(-1.0, L + 78.0);
  ModalSweepWorkspace ws;
  double worst = 0.0, worst_modes = 0.0, peak = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double x = along(rng);
    const double exact = closed_form(x);
    worst = railvsi::testing::worst_of(worst, std::abs(corrected.run(x, 0.0, 0, ws).max_abs_displacement_m[0] - exact));
    worst_modes = railvsi::testing::worst_of(worst_modes, std::abs(modes_only.run(x, 0.0, 0, ws).max_abs_displacement_m[0] - exact));
    peak = railvsi::testing::worst_of(peak, exact);
  }
  std::printf("[sweep] static midspan deflection with one mode vs the closed form, of the peak %.3e m: corrected "
              "%.2e, modes alone %.2e\n",
              peak, worst / peak, worst_modes / peak);
  ASSERT_GT(peak, 1e-4);
  // Hermite beam elements are exact under point loads: round-off alone
  // (measured 9.7e-13 of the peak).
  EXPECT_LT(worst, 5e-12 * peak);
  // One mode alone misses a share of it (measured 7.6e-3 of the peak).
  EXPECT_GT(worst_modes, 5e-3 * peak);
}

}  // namespace
}  // namespace railvsi

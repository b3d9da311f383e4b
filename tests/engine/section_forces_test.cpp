// Section forces, reactions and end rotations of a beam deck against
// Euler-Bernoulli closed forms: the static influence lines (exact: the FE
// nodal values of Hermite beams are exact for point loads, and the element
// end forces with the element's own loads subtracted are too), a train's
// quasi-static envelope by the classical rules, a moving force at very low
// speed on the FE and the exact modal rungs, and the two rungs at speed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/modal_moving_forces.hpp"
#include "analysis/static_influence.hpp"
#include "generators/bridge_2d.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kL = 20.0, kEI = 1.0e10, kMass = 10000.0;

std::shared_ptr<const StructureModel> beam(std::vector<std::pair<std::string, double>> points = {},
                                           double element_m = 0.5) {
  Bridge2dOptions b;
  b.spans_m = {kL};
  b.deck_EI_Nm2 = kEI;
  b.deck_mass_kg_per_m = kMass;
  b.damping_ratio = 0.02;
  b.element_length_m = element_m;
  b.output_points = std::move(points);
  return make_bridge_2d(b);
}

// Simply supported span, unit downward load at a: sagging moment and shear
// at x, left reaction, and the left end rotation (dv/dx, negative).
double moment(double a, double x) { return a <= x ? a * (kL - x) / kL : x * (kL - a) / kL; }
double shear_right_of_load(double a, double x) { return a <= x ? -a / kL : 1.0 - a / kL; }
double left_rotation(double a) { return -a * (kL - a) * (2 * kL - a) / (6 * kEI * kL); }

TEST(SectionForms, StaticInfluenceLinesAreTheBeamFormulas) {
  const auto s = beam();
  const StaticInfluence inf(*s);
  const SectionForms& f = inf.section_forms();
  ASSERT_TRUE(f.available()) << f.unavailable;
  ASSERT_EQ(f.points.size(), 1u);
  ASSERT_EQ(f.supports.size(), 2u);
  const SectionForms::Point& mid = f.points[0];
  const double x = kL / 2;
  double err_m = 0, err_v = 0, err_r = 0, err_t = 0;
  for (double a = 0.0; a <= kL + 1e-12; a += 0.13) {
    err_m = std::max({err_m, std::abs(inf.unit_form_value(mid.moment_left, a) - moment(a, x)),
                      std::abs(inf.unit_form_value(mid.moment_right, a) - moment(a, x))});
    if (std::abs(a - x) > 1e-9) {  // off the section both sides agree
      err_v = std::max({err_v, std::abs(inf.unit_form_value(mid.shear_left, a) - shear_right_of_load(a, x)),
                        std::abs(inf.unit_form_value(mid.shear_right, a) - shear_right_of_load(a, x))});
    }
    err_r = std::max({err_r, std::abs(inf.unit_form_value(f.supports[0].reaction, a) - (1 - a / kL)),
                      std::abs(inf.unit_form_value(f.supports[1].reaction, a) - a / kL)});
    err_t = railvsi::testing::worst_of(err_t, std::abs(inf.unit_form_value(f.supports[0].rotations.at(0), a) - left_rotation(a)));
  }
  std::printf("[sections] influence line errors: M %.2e m, V %.2e, R %.2e, theta %.2e rad (unit load)\n", err_m,
              err_v, err_r, err_t);
  // Round-off only (measured <= 1e-13 of the peak values 5 m, 0.5, 1, 6.4e-9 rad).
  EXPECT_LT(err_m, 1e-9 * 5.0);
  EXPECT_LT(err_v, 1e-9);
  EXPECT_LT(err_r, 1e-9);
  EXPECT_LT(err_t, 1e-9 * kL * kL / (16 * kEI));
  // A load standing on the section: the two sides differ by the load.
  const double vl = inf.unit_form_value(mid.shear_left, x), vr = inf.unit_form_value(mid.shear_right, x);
  EXPECT_NEAR(std::max(std::abs(vl), std::abs(vr)), 0.5, 1e-10);
  EXPECT_NEAR(vl - vr, 1.0, 1e-10);
}

TEST(SectionForms, QuasiStaticEnvelopeOfOneForceIsPlOverFour) {
  const auto s = beam();
  const StaticInfluence inf(*s);
  const double P = 170e3;
  const StaticSectionEnvelope e = inf.section_envelope({{0.0, P}});
  ASSERT_TRUE(e.unavailable.empty());
  EXPECT_NEAR(*e.max_abs_bending_moment_Nm[0], P * kL / 4, 1e-9 * P * kL);
  EXPECT_NEAR(*e.max_abs_shear_force_N[0], P / 2, 1e-9 * P);
  EXPECT_NEAR(e.max_reaction_N[0], P, 1e-9 * P);
  EXPECT_NEAR(e.max_reaction_N[1], P, 1e-9 * P);
  // End rotation: largest with the load at a = L (1 - 1/sqrt 3), P L^2/(9 sqrt 3 EI);
  // PL^2/(16 EI) with the load at midspan.
  const double theta = P * kL * kL / (9 * std::sqrt(3.0) * kEI);
  EXPECT_NEAR(e.max_abs_rotation_rad[0], theta, 1e-9 * theta);
  EXPECT_NEAR(std::abs(inf.unit_form_value(inf.section_forms().supports[0].rotations.at(0), kL / 2)) * P,
              P * kL * kL / (16 * kEI), 1e-9 * P * kL * kL / (16 * kEI));
}

TEST(SectionForms, TwoEqualLoadsFollowTheClassicalRule) {
  // Two loads P at spacing a: at midspan the maximum has one load on it,
  // M = P (L - a)/2; the absolute maximum is under a load placed a/4 from
  // midspan (the resultant and that load symmetric about midspan):
  // M = P (L - a/2)^2 / (2 L), valid for a < 0.586 L.
  const double a = 3.0, P = 100e3;
  const auto s = beam({{"mid", kL / 2}, {"abs", kL / 2 - a / 4}});
  const StaticInfluence inf(*s);
  const StaticSectionEnvelope e = inf.section_envelope({{0.0, P}, {a, P}});
  EXPECT_NEAR(*e.max_abs_bending_moment_Nm[0], P * (kL - a) / 2, 1e-9 * P * kL);
  EXPECT_NEAR(*e.max_abs_bending_moment_Nm[1], P * (kL - a / 2) * (kL - a / 2) / (2 * kL), 1e-9 * P * kL);
  // Largest reaction: one load on the support, the other a inside: P (2 - a/L).
  EXPECT_NEAR(e.max_reaction_N[0], P * (2 - a / kL), 1e-9 * P);
}

// LM71 (EN 1991-2 6.3.2: 4 x 250 kN at 1.6 m, 80 kN/m beyond 0.8 m of the
// outer loads, where unfavourable) on the midspan moment's influence line,
// the triangle x/2 to its peak L/4. Shifting the group by d from symmetric
// keeps the point loads' part at P (L - 3.2) for |d| <= 0.8 (two loads on
// each side of the peak) and frees area d^2/2 from under the load-free
// window, so the maximum is at d = 0.8 (a load on midspan):
// M = P (L - 3.2) + q (L^2/8 - (1.6 L - 5.12) + 0.32).
TEST(SectionForms, Lm71MidspanMomentIsTheHandCalculation) {
  const auto s = beam({{"mid", kL / 2}});
  const StaticInfluence inf(*s);
  const SectionForms& f = inf.section_forms();
  const double P = 250e3, q = 80e3;
  const double expected = P * (kL - 3.2) + q * (kL * kL / 8 - (1.6 * kL - 5.12) + 0.32);
  const double m = std::max(inf.lm71_form(f.points[0].moment_left).max_deflection_m,
                            inf.lm71_form(f.points[0].moment_right).max_deflection_m);
  std::printf("[sections] LM71 midspan moment, 20 m: %.6e Nm, hand %.6e Nm (%+.2e)\n", m, expected, m / expected - 1);
  // Measured: the hand value to 3e-12 (the golden-section search stops
  // within 1e-9 m of the group position; the two-point Gauss areas are
  // exact on the linear pieces).
  EXPECT_NEAR(m, expected, 1e-10 * expected);
}

TEST(SectionForms, AbsentWithAReasonForADeckWithoutBeam) {
  const auto b = beam();
  StructureInfo info = b->info();
  info.deck_beam.reset();  // as an imported or 3D model
  const auto s = std::make_shared<const StructureModel>(b->K(), b->M(), b->C(), b->rails(), b->outputs(), info);
  Scene scene;
  scene.structure = s;
  scene.train.moving_forces = {{0.0, 1e5}};
  scene.speed_mps = 50.0;
  scene.analysis.dt_s = 2e-3;
  for (const Result& r : {Simulation(scene).run(), run_modal_moving_forces(scene)}) {
    ASSERT_TRUE(r.status.ok());
    EXPECT_FALSE(r.summary.section_forces_note.empty());
    EXPECT_TRUE(r.summary.supports.empty());
    EXPECT_FALSE(r.summary.points.at(0).max_abs_bending_moment_Nm.has_value());
    EXPECT_FALSE(r.summary.points.at(0).max_abs_shear_force_N.has_value());
  }
}

// A force crossing at very low speed (speed parameter v/(2 f1 L) = 1.5e-3)
// on the FE and the modal rungs: the envelopes are the static maxima.
TEST(SectionForces, SlowMovingForceGivesTheStaticMaxima) {
  const double P = 170e3, v = 0.1;
  Scene scene;
  scene.structure = beam({}, 1.0);
  scene.train.moving_forces = {{0.0, P}};
  scene.speed_mps = v;
  scene.start_x_m = 0.0;
  scene.analysis.dt_s = 0.02;  // 0.002 m per step
  scene.analysis.duration_s = kL / v;
  const double M = P * kL / 4, V = P / 2, R = P, theta = P * kL * kL / (9 * std::sqrt(3.0) * kEI);
  ModalMovingForceOptions mo;
  mo.max_frequency_hz = 60.0;
  const Result fe = Simulation(scene).run();
  const Result modal = run_modal_moving_forces(scene, mo);
  for (const Result* r : {&fe, &modal}) {
    ASSERT_TRUE(r->status.ok()) << r->status.message();
    const RunSummary& s = r->summary;
    ASSERT_TRUE(s.points.at(0).max_abs_bending_moment_Nm);
    ASSERT_EQ(s.supports.size(), 2u);
    const double em = *s.points[0].max_abs_bending_moment_Nm / M - 1, ev = *s.points[0].max_abs_shear_force_N / V - 1;
    const double er = s.supports[0].max_reaction_N / R - 1, et = s.supports[0].max_abs_rotation_rad / theta - 1;
    std::printf("[sections] %s, v = %g m/s: M %+.2e, V %+.2e, R %+.2e, theta %+.2e (relative to the static "
                "closed form)\n",
                r == &fe ? "FE" : "modal", v, em, ev, er, et);
    // Measured: |errors| <= 5e-6 on both rungs (the load moves 2 mm per
    // step; the dynamic part at this speed is of that order).
    EXPECT_LT(std::abs(em), 2e-5);
    EXPECT_LT(std::abs(ev), 2e-5);
    EXPECT_LT(std::abs(er), 2e-5);
    EXPECT_LT(std::abs(et), 2e-5);
  }
}

// At speed, the modal rung's section forces (mode-acceleration, modes up to
// 60 Hz) against the FE rung at a fine step: the two rungs share no code
// path for them beyond the forms.
TEST(SectionForces, ModalRungMatchesTheFeRungAtSpeed) {
  Scene scene;
  scene.structure = beam({{"quarter", 5.0}, {"mid", 10.0}}, 0.5);
  scene.train.moving_forces = {{0.0, 170e3}, {3.0, 170e3}, {11.0, 170e3}, {14.0, 170e3}};
  scene.speed_mps = 250 / 3.6;
  scene.analysis.dt_s = 2.5e-4;
  ModalMovingForceOptions mo;
  mo.max_frequency_hz = 60.0;
  const Result fe = Simulation(scene).run();
  const Result modal = run_modal_moving_forces(scene, mo);
  ASSERT_TRUE(fe.status.ok() && modal.status.ok());
  double worst = 0.0;
  for (std::size_t p = 0; p < 2; ++p) {
    const double m = *modal.summary.points[p].max_abs_bending_moment_Nm / *fe.summary.points[p].max_abs_bending_moment_Nm - 1;
    const double v = *modal.summary.points[p].max_abs_shear_force_N / *fe.summary.points[p].max_abs_shear_force_N - 1;
    std::printf("[sections] modal vs FE at 250 km/h, %s: M %+.2e, V %+.2e\n", fe.summary.points[p].name.c_str(), m, v);
    worst = std::max({worst, std::abs(m), std::abs(v)});
  }
  for (std::size_t i = 0; i < 2; ++i) {
    const double r = modal.summary.supports[i].max_reaction_N / fe.summary.supports[i].max_reaction_N - 1;
    const double t = modal.summary.supports[i].max_abs_rotation_rad / fe.summary.supports[i].max_abs_rotation_rad - 1;
    std::printf("[sections] modal vs FE at 250 km/h, %s: R %+.2e, theta %+.2e\n", fe.summary.supports[i].name.c_str(),
                r, t);
    worst = std::max({worst, std::abs(r), std::abs(t)});
  }
  // Measured worst 4.9e-3 (shear at the quarter point): the modes above 60 Hz
  // and the FE rung's HHT period error at this step.
  EXPECT_LT(worst, 7e-3);
}

// The sweep carries each form's influence line as a cubic per rail element
// (fitted at four interior points): at many axle positions, inside elements
// and on nodes, a quasi-static sweep (modes far above the load frequency)
// gives the exact static values of StaticInfluence.
TEST(SectionForces, ModalSweepStaticPartIsTheExactInfluenceLine) {
  const auto s = beam({{"quarter", 5.0}, {"mid", 10.0}}, 0.5);
  ModalBasisOptions o;
  o.max_frequency_hz = 60.0;
  const ModalBasis basis(s, o);
  const auto sections = modal_section_forces(basis, {0});
  ASSERT_NE(sections, nullptr);
  Train train;
  train.moving_forces = {{0.0, 1.0}};
  const ModalSweep sweep(basis, train, {0}, 1.0, sections);
  // One step per run of a force at 0 speed standing at x: the first record
  // is the static response, so the envelope is |static value| per form.
  ModalSweepWorkspace ws;
  double worst = 0.0, worst_fit = 0.0;
  for (double x : {0.0, 0.5, 1.3, 5.0, 7.77, 10.0, 12.25, 19.5, 20.0}) {
    const ModalSweepRun run = sweep.run(x, 0.0, 0, ws);
    ASSERT_TRUE(run.sections.has_value());
    RunSummary sum;
    sum.points.resize(2);
    run.sections->summarize(sum);
    const auto& f = sections->forms();
    for (std::size_t p = 0; p < 2; ++p) {
      const double m = std::max(std::abs(sections->statics().unit_form_value(f.points[p].moment_left, x)),
                                std::abs(sections->statics().unit_form_value(f.points[p].moment_right, x)));
      const double mm = moment(x, s->outputs()[p].x_m);
      worst_fit = railvsi::testing::worst_of(worst_fit, std::abs(*sum.points[p].max_abs_bending_moment_Nm - m));
      worst = railvsi::testing::worst_of(worst, std::abs(m - mm));
    }
  }
  std::printf("[sections] sweep's cubic vs exact influence line: %.1e m; exact vs closed form: %.1e m\n", worst_fit,
              worst);
  // Measured: 4.9e-15 and 7.3e-12 m per unit load (peak 5 m).
  EXPECT_LT(worst_fit, 1e-13);
  EXPECT_LT(worst, 2e-11);
}

// With a ballasted track the deck carries the ballast springs' forces: the
// moment from the element left of a section and from the element right of
// it (two independent rows, each with its own springs) must agree, and the
// sum of the reactions must balance the springs' forces on the deck.
TEST(SectionForces, TrackOnTheDeckKeepsTheSectionInEquilibrium) {
  Bridge2dOptions b;
  b.spans_m = {kL};
  b.deck_EI_Nm2 = kEI;
  b.deck_mass_kg_per_m = kMass;
  b.damping_ratio = 0.02;
  b.track = TrackOptions{};
  b.track->approach_m = 6.0;
  b.track->exit_m = 6.0;
  const auto s = make_bridge_2d(b);
  const StaticInfluence inf(*s);
  const SectionForms& f = inf.section_forms();
  ASSERT_TRUE(f.available());
  EXPECT_FALSE(f.rail_is_deck.at(0));
  double worst = 0.0, peak = 0.0;
  for (double a = -5.0; a <= kL + 5.0; a += 0.37) {
    const double ml = inf.unit_form_value(f.points[0].moment_left, a), mr = inf.unit_form_value(f.points[0].moment_right, a);
    worst = railvsi::testing::worst_of(worst, std::abs(ml - mr));
    peak = railvsi::testing::worst_of(peak, std::abs(ml));
  }
  std::printf("[sections] track on deck: |M_left - M_right| <= %.2e of the peak %.3g m\n", worst / peak, peak);
  EXPECT_LT(worst, 1e-9 * peak);
  // A unit load on the rail at midspan, solved apart (Eigen's LDLT, not
  // CHOLMOD); the deck as a free body: its reactions balance the ballast
  // springs' forces, and the moment at midspan is that of the forces left
  // of it.
  Vector load = Vector::Zero(s->num_dofs());
  const auto row = s->rails()[0].locate(kL / 2);
  for (int k = 0; k < 4; ++k)
    if (row->dof[k] >= 0) load[row->dof[k]] -= row->weight[k];
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(s->K());
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Vector u = ldlt.solve(load), zero = Vector::Zero(s->num_dofs());
  const RailLine& deck = s->info().deck_line;
  double springs = 0.0, springs_moment = 0.0;
  for (const DeckLink& l : s->info().deck_beam->links) {
    const DeckPoint at = deck_point(deck, l.x_m);
    double w_u = 0.0;
    for (int k = 0; k < 4; ++k)
      if (deck.element_dofs[at.element][k] >= 0) w_u += at.w[k] * u[deck.element_dofs[at.element][k]];
    const double up = l.k_N_per_m * (u[l.dof] - w_u);
    springs += up;
    if (l.x_m < kL / 2) springs_moment += up * (kL / 2 - l.x_m);
  }
  const double r1 = f.forms[f.supports[0].reaction].state_value(u, zero, zero);
  const double r2 = f.forms[f.supports[1].reaction].state_value(u, zero, zero);
  const double m = f.forms[f.points[0].moment_left].state_value(u, zero, zero);
  const double m_free_body = r1 * kL / 2 + springs_moment;
  std::printf("[sections] track on deck, unit load at midspan: reactions %.6f + springs %.6f = %.1e; moment %.6f m, "
              "free body %.6f m (bare beam %.1f)\n",
              r1 + r2, springs, r1 + r2 + springs, m, m_free_body, kL / 4);
  EXPECT_NEAR(r1 + r2, -springs, 1e-9);
  EXPECT_NEAR(m, m_free_body, 1e-9 * kL);
  // And the influence line (CHOLMOD, reciprocity) gives the same moment.
  EXPECT_NEAR(inf.unit_form_value(f.points[0].moment_left, kL / 2), m, 1e-9 * kL);
}

}  // namespace
}  // namespace railvsi

// Section forces, reactions and end rotations on the modal interaction rung
// (a Simulation on the modal structure), by the mode-acceleration method:
// against the closed forms of a simply supported Euler-Bernoulli span, and
// against the FE rung on the same scene (the FE rung evaluates the forms on
// its DOFs; the modal rung shares only the forms with it: its static part
// comes from the influence lines, its dynamic part from the modes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "generators/bridge_2d.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "test_scenes.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kL = 20.0, kEI = 1.0e10, kMass = 10000.0, kP = 170e3;

// The simply supported span, 0.5 m elements, 2 % Rayleigh damping.
Bridge2dOptions span_options(std::vector<std::pair<std::string, double>> points) {
  Bridge2dOptions b;
  b.spans_m = {kL};
  b.deck_EI_Nm2 = kEI;
  b.deck_mass_kg_per_m = kMass;
  b.damping_ratio = 0.02;
  b.element_length_m = 0.5;
  b.output_points = std::move(points);
  return b;
}
std::shared_ptr<const StructureModel> span(std::vector<std::pair<std::string, double>> points) {
  return make_bridge_2d(span_options(std::move(points)));
}

Scene on_modes(Scene s, int modes) {
  s.analysis.structure_backend = StructureBackend::kModal;
  s.analysis.modal_modes = modes;
  return s;
}

// The four section quantities of a run, relative to references.
struct Quantities {
  double moment = 0.0, shear = 0.0, reaction = 0.0, rotation = 0.0;
};
Quantities of(const RunSummary& s, std::size_t point = 0, std::size_t support = 0) {
  EXPECT_TRUE(s.section_forces_note.empty()) << s.section_forces_note;
  EXPECT_TRUE(s.points.at(point).max_abs_bending_moment_Nm.has_value());
  EXPECT_GT(s.supports.size(), support);
  if (!s.points.at(point).max_abs_bending_moment_Nm || s.supports.size() <= support) return {};
  return {*s.points[point].max_abs_bending_moment_Nm, *s.points[point].max_abs_shear_force_N,
          s.supports[support].max_reaction_N, s.supports[support].max_abs_rotation_rad};
}
Quantities relative_error(const Quantities& a, const Quantities& ref) {
  return {a.moment / ref.moment - 1, a.shear / ref.shear - 1, a.reaction / ref.reaction - 1,
          a.rotation / ref.rotation - 1};
}
double worst(const Quantities& e) {
  return std::max({std::abs(e.moment), std::abs(e.shear), std::abs(e.reaction), std::abs(e.rotation)});
}

class ModalInteractionClosedForm : public ::testing::TestWithParam<int> {};

// A force P standing at midspan (no motion: the run starts from the static
// state and stays there): M = PL/4, V = P/2 on either side, R = P/2,
// end rotation PL^2/(16 EI). The mode-acceleration method gives the static
// value exactly whatever the mode count (with the displacement of one mode
// alone the moment would be 8/pi^2 = 81 % of it).
TEST_P(ModalInteractionClosedForm, ForceAtMidspanGivesTheBeamFormulas) {
  Scene scene;
  scene.structure = span({{"mid", kL / 2}});
  scene.train.moving_forces = {{0.0, kP}};
  scene.speed_mps = 0.0;
  scene.start_x_m = kL / 2;
  scene.analysis.dt_s = 1e-3;
  scene.analysis.duration_s = 0.01;
  const Result r = Simulation(on_modes(scene, GetParam())).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const Quantities ref{kP * kL / 4, kP / 2, kP / 2, kP * kL * kL / (16 * kEI)};
  const Quantities e = relative_error(of(r.summary), ref);
  std::printf("[modal sections] P at midspan, %d modes: M %+.2e V %+.2e R %+.2e theta %+.2e\n", GetParam(), e.moment,
              e.shear, e.reaction, e.rotation);
  // Measured: <= 3e-12 for 1, 4 and 16 modes (round-off of the factor of K).
  EXPECT_LT(worst(e), 1e-10);
}

// A force crossing at 0.1 m/s (speed parameter v/(2 f1 L) = 1.5e-3): the
// envelopes are the static maxima, M = PL/4, V = P/2 (right beside the
// section), R = P (the force at the support) and the largest end rotation
// PL^2/(9 sqrt(3) EI), with the force at L(1 - 1/sqrt(3)) (at midspan it is
// PL^2/(16 EI), checked above).
TEST_P(ModalInteractionClosedForm, SlowCrossingGivesTheStaticMaxima) {
  Scene scene;
  scene.structure = span({{"mid", kL / 2}});
  scene.train.moving_forces = {{0.0, kP}};
  const double v = 0.1;
  scene.speed_mps = v;
  scene.start_x_m = 0.0;
  scene.analysis.dt_s = 0.02;  // 2 mm per step
  scene.analysis.duration_s = kL / v;
  const Result r = Simulation(on_modes(scene, GetParam())).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const Quantities ref{kP * kL / 4, kP / 2, kP, kP * kL * kL / (9 * std::sqrt(3.0) * kEI)};
  const Quantities e = relative_error(of(r.summary), ref);
  std::printf("[modal sections] slow crossing, %d modes: M %+.2e V %+.2e R %+.2e theta %+.2e\n", GetParam(),
              e.moment, e.shear, e.reaction, e.rotation);
  // Measured: |errors| <= 5.8e-6 for 1, 4 and 16 modes (the force moves 2 mm
  // per step; the dynamic part at this speed is of that order), as on the
  // FE and the exact modal rungs (section_forces_test).
  EXPECT_LT(worst(e), 2e-5);
}

INSTANTIATE_TEST_SUITE_P(Modes, ModalInteractionClosedForm, ::testing::Values(1, 4, 16),
                         [](const auto& info) { return std::to_string(info.param) + "modes"; });

// One ICE3 coach (multibody, linear Hertz contact) at 200 km/h.
Scene ice3_at_200(std::shared_ptr<const StructureModel> structure) {
  Scene scene;
  scene.structure = std::move(structure);
  scene.train.vehicles.push_back({make_car_2d(testing::ice3_coach()), 0.0});
  scene.speed_mps = 200 / 3.6;
  scene.analysis.dt_s = 2.5e-4;
  scene.analysis.contact.law = "linear-hertz";
  return scene;
}

// The span with a ballasted track (a 30 m approach holds the coach at
// t = 0): the deck carries the ballast springs' forces, which the forms
// read at the track's DOFs.
Scene ice3_on_track(bool damped) {
  Bridge2dOptions b = span_options({{"quarter", kL / 4}, {"mid", kL / 2}});
  if (!damped) b.damping_ratio = 0.0;
  TrackOptions t;
  t.approach_m = 30.0;
  t.exit_m = 6.0;
  if (!damped) t.pad_c_Ns_per_m = t.ballast_c_Ns_per_m = t.subballast_c_Ns_per_m = 0.0;
  b.track = t;
  return ice3_at_200(make_bridge_2d(b));
}

// The worst relative error of the four quantities at both output points
// and both supports of `modal` against `fe`, printed per point.
double worst_against(const RunSummary& modal, const RunSummary& fe, const char* what) {
  double w = 0.0;
  for (std::size_t p = 0; p < 2; ++p)
    for (std::size_t s = 0; s < 2; ++s) {
      const Quantities e = relative_error(of(modal, p, s), of(fe, p, s));
      w = railvsi::testing::worst_of(w, worst(e));
      std::printf("[modal sections] %s, %d modes vs FE, %s/%s: M %+.2e V %+.2e R %+.2e theta %+.2e\n", what,
                  modal.fidelity.modes, fe.points[p].name.c_str(), fe.supports[s].name.c_str(), e.moment, e.shear,
                  e.reaction, e.rotation);
    }
  std::printf("[modal sections] %s, %d modes: worst %.2e\n", what, modal.fidelity.modes, w);
  return w;
}

// One ICE3 coach (multibody, linear Hertz contact) at 200 km/h over the
// span, its wheels on the deck line (no track; Rayleigh damping, so the
// modes are uncoupled): the modal rung with growing mode counts against the
// FE rung at the same step. The error falls with the mode count.
TEST(ModalInteractionSections, ConvergeToTheFeRungWithTheModeCount) {
  const Scene scene = ice3_at_200(span({{"quarter", kL / 4}, {"mid", kL / 2}}));
  const Result fe = Simulation(scene).run();
  ASSERT_TRUE(fe.status.ok()) << fe.status.message();
  const std::vector<int> modes = {1, 2, 4, 8, 16};
  // Measured worst relative errors (M, V, R, theta at both points and
  // supports), with the static correction (the default): 5.63e-2, 1.08e-2,
  // 1.44e-2, 2.69e-4, 3.98e-5 (the shear at midspan, the quantity the high
  // modes carry most); without it 3.57e-2, 1.80e-2, 1.04e-2, 1.85e-4,
  // 1.57e-4.
  const std::vector<double> bound = {7e-2, 1.5e-2, 2e-2, 4e-4, 6e-5};
  std::vector<double> w;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const Result m = Simulation(on_modes(scene, modes[i])).run();
    ASSERT_TRUE(m.status.ok()) << m.status.message();
    w.push_back(worst_against(m.summary, fe.summary, "ICE3 200 km/h, no track"));
    EXPECT_LT(w.back(), bound[i]) << modes[i] << " modes";
  }
  EXPECT_LT(w.back(), w.front() / 100);
}

// With every mode and no damping the modal rung is the FE rung in other
// coordinates (HHT commutes with the change of basis): the section forces
// of a deck under a ballasted track (the ballast springs' terms read on
// the modes) agree to round-off.
TEST(ModalInteractionSections, WithEveryModeTheTrackedDeckIsTheFeRung) {
  const Scene scene = ice3_on_track(/*damped=*/false);
  const Result fe = Simulation(scene).run();
  ASSERT_TRUE(fe.status.ok()) << fe.status.message();
  const Result m = Simulation(on_modes(scene, scene.structure->num_dofs())).run();
  ASSERT_TRUE(m.status.ok()) << m.status.message();
  // Measured 2.1e-10 (419 modes: every mode of the model).
  EXPECT_LT(worst_against(m.summary, fe.summary, "ICE3 200 km/h, undamped track"), 1e-9);
}

// With the track's dampers (pads, ballast: a non-proportional damping the
// modes keep only as phi^T C phi / 2 omega) the errors do not fall with
// the mode count (docs/method.md "The modal structure"): the bound guards the
// measured level, it claims no convergence.
TEST(ModalInteractionSections, DampedTrackStaysWithinTheMeasuredErrors) {
  const Scene scene = ice3_on_track(/*damped=*/true);
  const Result fe = Simulation(scene).run();
  ASSERT_TRUE(fe.status.ok()) << fe.status.message();
  for (int modes : {4, 16, 64}) {
    const Result m = Simulation(on_modes(scene, modes)).run();
    ASSERT_TRUE(m.status.ok()) << m.status.message();
    // Measured with the static correction (the default) 5.0e-3, 3.1e-3,
    // 1.21e-2; without it 7.8e-3, 2.8e-3, 3.9e-3 (256 modes: 8.0e-3).
    EXPECT_LT(worst_against(m.summary, fe.summary, "ICE3 200 km/h, ballasted track"), 1.6e-2) << modes << " modes";
  }
}

// jobs/examples/viaduct-ice3.json without its track: the whole ICE3 at
// 300 km/h over three 25 m spans, unilateral Hertz on the example's
// profile, wheels on the deck beam. Moment and end rotation converge
// fast; shear and reaction read the contact forces directly (V jumps by
// each wheel load), and those converge slowly on the modal rung: they
// depend on the local flexibility under a wheel, which the kept modes
// miss and the static correction (the default) restores only statically
// (docs/method.md "The modal structure").
TEST(ModalInteractionSections, ViaductShearAndReactionConvergeSlowerThanMoment) {
  const std::string path = RAILVSI_SOURCE_DIR "/jobs/examples/viaduct-ice3.json";
  nlohmann::json doc = read_json_file(path);
  doc["structure"]["track"] = nullptr;
  const Scene scene = parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs/examples", path);
  const Result fe = Simulation(scene).run();
  ASSERT_TRUE(fe.status.ok()) << fe.status.message();
  struct Rung {
    double cutoff_hz;
    double moment_rotation, shear_reaction;  // bounds on the worst relative errors
  };
  // Measured worst |relative error| of M and theta / of V and R over the
  // three midspans and four supports, with the static correction: 60 Hz
  // (9 modes) 3.3e-3 / 3.5e-2, 400 Hz (24 modes) 7.4e-5 / 5.6e-3; without
  // it 2.8e-3 / 6.7e-2 and 2.7e-4 / 6.0e-3 (100 Hz: 4.6e-3 / 5.2e-2;
  // 200 Hz: 9.2e-4 / 4.8e-2).
  for (const Rung& rung : {Rung{60.0, 4e-3, 5e-2}, Rung{400.0, 1.2e-4, 8e-3}}) {
    Scene s = scene;
    s.analysis.structure_backend = StructureBackend::kModal;
    s.analysis.modal_cutoff_hz = rung.cutoff_hz;
    const Result m = Simulation(s).run();
    ASSERT_TRUE(m.status.ok()) << m.status.message();
    double mt = 0.0, vr = 0.0;
    for (std::size_t p = 0; p < 3; ++p) {
      const Quantities e = relative_error(of(m.summary, p, p), of(fe.summary, p, p));
      mt = railvsi::testing::worst_of(mt, std::abs(e.moment));
      vr = railvsi::testing::worst_of(vr, std::abs(e.shear));
    }
    for (std::size_t i = 0; i < 4; ++i) {
      const Quantities e = relative_error(of(m.summary, 0, i), of(fe.summary, 0, i));
      mt = railvsi::testing::worst_of(mt, std::abs(e.rotation));
      vr = railvsi::testing::worst_of(vr, std::abs(e.reaction));
    }
    std::printf("[modal sections] viaduct, ICE3 300 km/h, %g Hz (%d modes): M, theta %.2e; V, R %.2e\n",
                rung.cutoff_hz, m.summary.fidelity.modes, mt, vr);
    EXPECT_LT(mt, rung.moment_rotation);
    EXPECT_LT(vr, rung.shear_reaction);
  }
}

// No section forces where none can be computed (a deck that is not a beam)
// or none are asked: the keys stay empty and the note says why, never 0.
TEST(ModalInteractionSections, LeftOutWithAReason) {
  const auto b = span({{"mid", kL / 2}});
  StructureInfo info = b->info();
  info.deck_beam.reset();  // as an imported or 3D model
  Scene scene;
  scene.structure = std::make_shared<const StructureModel>(b->K(), b->M(), b->C(), b->rails(), b->outputs(), info);
  scene.train.moving_forces = {{0.0, kP}};
  scene.speed_mps = 50.0;
  scene.analysis.dt_s = 2e-3;
  Scene not_asked = scene;
  not_asked.structure = b;
  not_asked.fidelity.asks = std::vector<std::string>{"deck"};
  for (const Scene* s : {&scene, &not_asked}) {
    const Result r = Simulation(on_modes(*s, 4)).run();
    ASSERT_TRUE(r.status.ok()) << r.status.message();
    std::printf("[modal sections] note: %s\n", r.summary.section_forces_note.c_str());
    EXPECT_NE(r.summary.section_forces_note.find(s == &scene ? "beam decks" : "not asked"), std::string::npos);
    EXPECT_TRUE(r.summary.supports.empty());
    EXPECT_FALSE(r.summary.points.at(0).max_abs_bending_moment_Nm.has_value());
    EXPECT_FALSE(r.summary.points.at(0).max_abs_shear_force_N.has_value());
  }
}

}  // namespace
}  // namespace railvsi

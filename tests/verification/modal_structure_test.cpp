// The interaction rung on a modal structure converges to the finite-element
// rung as modes are added: the same scene (multibody train, Hertz contact,
// irregularity) run with "structure": "fe" and "structure": "modal" at
// growing cut-offs. Quantities are the envelopes a study stores: deck
// displacement, deck acceleration after the code filter (EN 1990 A2.4.4.2),
// minimum contact force and wheel unloading dQ/Q.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fmt/format.h>

#include "envelopes/job_envelopes.hpp"
#include "generators/deck_3d.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"

namespace railvsi {
namespace {

struct Errors {
  int modes = 0;
  double displacement = 0.0;  // relative, max over output points
  double acceleration = 0.0;  // filtered, relative, max over output points
  double min_force = 0.0;     // relative to the FE minimum contact force
  double unloading = 0.0;     // |dQ/Q modal - dQ/Q FE|, absolute
  double wall_s = 0.0;
};

JobEnvelopes envelopes_of(const Scene& scene, double cutoff_hz, int* modes = nullptr, double* wall_s = nullptr) {
  const Result r = Simulation(scene).run();
  EXPECT_TRUE(r.status.ok()) << r.status.message();
  if (modes) std::sscanf(r.summary.fidelity.structure_backend.c_str(), "modal (%d", modes);
  if (wall_s) *wall_s = r.summary.wall_s;
  return compute_envelopes(r, scene.analysis.dt_s, scene.analysis.history_stride, cutoff_hz);
}

double rel(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

Errors compare(const JobEnvelopes& m, const JobEnvelopes& fe) {
  Errors e;
  for (std::size_t p = 0; p < fe.points.size(); ++p) {
    e.displacement = std::max(e.displacement, rel(*m.points[p].max_abs_displacement_m, *fe.points[p].max_abs_displacement_m));
    e.acceleration =
        std::max(e.acceleration, rel(*m.points[p].max_abs_acceleration_mps2, *fe.points[p].max_abs_acceleration_mps2));
  }
  if (fe.min_contact_force_N) {
    e.min_force = rel(*m.min_contact_force_N, *fe.min_contact_force_N);
    e.unloading = std::abs(*m.max_unloading_ratio - *fe.max_unloading_ratio);
  }
  return e;
}

std::vector<Errors> ladder(Scene scene, double filter_hz, const std::vector<double>& cutoffs_hz, double* fe_wall_s) {
  scene.analysis.structure_backend = StructureBackend::kFiniteElements;
  const JobEnvelopes fe = envelopes_of(scene, filter_hz, nullptr, fe_wall_s);
  std::vector<Errors> out;
  for (double c : cutoffs_hz) {
    Scene s = scene;
    s.analysis.structure_backend = StructureBackend::kModal;
    s.analysis.modal_cutoff_hz = c;
    int modes = 0;
    double wall = 0.0;
    Errors e = compare(envelopes_of(s, filter_hz, &modes, &wall), fe);
    e.modes = modes;
    e.wall_s = wall;
    fmt::print("cutoff {:6.0f} Hz {:4d} modes: displacement {:.3e} acceleration {:.3e} min force {:.3e} dQ/Q {:.3e} "
               "wall {:.2f} s\n",
               c, e.modes, e.displacement, e.acceleration, e.min_force, e.unloading, e.wall_s);
    out.push_back(e);
  }
  fmt::print("FE wall {:.2f} s\n", *fe_wall_s);
  return out;
}

// jobs/examples/viaduct-ice3.json: ICE3 at 300 km/h over three simply
// supported 25 m spans (f0 = 5 Hz) on ballasted track, unilateral Hertz,
// the example's irregularity profile.
Scene viaduct() { return load_scene(RAILVSI_SOURCE_DIR "/jobs/examples/viaduct-ice3.json"); }

TEST(ModalStructure, ViaductWithTrackConvergesToTheFiniteElementRung) {
  const double filter_hz = 45.0;  // max(30 Hz, 1.5 f0, f3 = 9 f0) for 25 m spans at f0 = 5 Hz
  double fe_wall = 0.0;
  const auto e = ladder(viaduct(), filter_hz, {30, 60, 100, 200, 400, 800}, &fe_wall);
  ASSERT_FALSE(e.empty());
}

TEST(ModalStructure, ThreeDimensionalDeckConvergesToTheFiniteElementRung) {
  Deck3dOptions o;
  o.spans_m = {25.0};
  o.target_dofs = 5000;
  o.approach_m = 60.0;
  o.exit_m = 20.0;
  Scene scene;
  scene.structure = make_deck_3d(o).model;
  scene.train = load_library_train("ICE3");
  scene.train.vehicles.resize(2);
  scene.speed_mps = 300 / 3.6;
  scene.analysis.dt_s = 2.5e-4;
  scene.analysis.contact.law = "hertz";
  scene.analysis.contact.rail_lines = {0, 1};
  double fe_wall = 0.0;
  const auto e = ladder(scene, 30.0, {30, 60, 100, 200, 400, 800}, &fe_wall);
  ASSERT_FALSE(e.empty());
}

}  // namespace
}  // namespace railvsi

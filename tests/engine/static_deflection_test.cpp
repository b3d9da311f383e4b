// Static deflection of the generated beam against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/input_error.hpp"
#include "generators/bridge_2d.hpp"
#include "solver/cholmod_operator.hpp"
#include "solver/structure_backend.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi {
namespace {

Bridge2dOptions simple_beam(double L, double EI, double m) {
  Bridge2dOptions o;
  o.spans_m = {L};
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = m;
  o.element_length_m = 1.0;
  return o;
}

TEST(StaticDeflection, MidspanPointLoadEqualsPL3Over48EI) {
  const double L = 25.0, EI = 7.0e10, P = 170e3;
  Scene scene;
  scene.structure = make_bridge_2d(simple_beam(L, EI, 15000.0));
  scene.train.moving_forces = {{0.0, P}};
  TrainLayout layout(scene.train, scene.analysis.contact);
  const CholmodOperator statics(*scene.structure, {0.0, 0.0, 1.0}, {.rail_flexibility = false});
  const StaticState st = static_equilibrium(scene, layout, 0.5 * L, statics);
  const int dof = scene.structure->outputs().front().dof;
  const double expected = -P * L * L * L / (48.0 * EI);
  EXPECT_NEAR(st.u_s[dof] / expected, 1.0, 1e-9);
}

// The modal backend's static state is that of its modes: for a midspan load
// on a simply supported beam, phi_k(L/2)^2 / omega_k^2 summed over the kept
// modes, 2 L^3 / (pi^4 EI) sum_{k odd} 1/k^4 (the even modes have a node at
// midspan), which tends to L^3 / (48 EI) (sum over all odd k = pi^4/96).
TEST(StaticDeflection, ModalStaticStateIsTheTruncatedModalSeries) {
  const double L = 25.0, EI = 7.0e10, P = 170e3;
  Scene scene;
  scene.structure = make_bridge_2d(simple_beam(L, EI, 15000.0));
  scene.train.moving_forces = {{0.0, P}};
  TrainLayout layout(scene.train, scene.analysis.contact);
  const int dof = scene.structure->outputs().front().dof;
  double series = 0.0;
  for (int modes = 1; modes <= 5; ++modes) {
    if (modes % 2 == 1) series += 1.0 / std::pow(modes, 4);
    StructureOperatorOptions o;
    o.structure_backend = StructureBackend::kModal;
    o.modal_modes = modes;
    o.rail_flexibility = false;
    const auto statics = make_structure_operator(scene.structure, {0.0, 0.0, 1.0}, o);
    const StaticState st = static_equilibrium(scene, layout, 0.5 * L, *statics);
    const double u_mid = statics->coordinates(*scene.structure).at(dof, st.u_s);
    const double expected = -P * 2.0 * L * L * L / (std::pow(std::numbers::pi, 4) * EI) * series;
    // The beam's modes from 1 m Hermite elements are those of the
    // continuous beam to ~1e-7 per mode: measured 3.0e-7 (1 mode) to 8.7e-7
    // (5 modes).
    EXPECT_NEAR(u_mid / expected, 1.0, 3e-6) << modes << " modes";
  }
}

TEST(StaticDeflection, OffNodeLoadMatchesBeamFormula) {
  // Load at a = 7.3 m (between nodes): midspan deflection P b (3L^2 - 4b^2)/(48 EI), b = L - a... for a < L/2
  const double L = 20.0, EI = 5.0e9, P = 1.0e5, a = 7.3;
  Scene scene;
  scene.structure = make_bridge_2d(simple_beam(L, EI, 1000.0));
  scene.train.moving_forces = {{0.0, P}};
  TrainLayout layout(scene.train, scene.analysis.contact);
  const CholmodOperator statics(*scene.structure, {0.0, 0.0, 1.0}, {.rail_flexibility = false});
  const StaticState st = static_equilibrium(scene, layout, a, statics);
  const int dof = scene.structure->outputs().front().dof;
  // Deflection at midspan (x = L/2 >= a) from a load at a: P a (3L^2 - 4a^2) / (48 EI).
  const double expected = -P * a * (3.0 * L * L - 4.0 * a * a) / (48.0 * EI);
  // Hermite interpolation of the load is consistent, not exact, between nodes.
  EXPECT_NEAR(st.u_s[dof] / expected, 1.0, 1e-3);
}

}  // namespace
}  // namespace railvsi

namespace railvsi {
namespace {

// A negative bearing spring makes the stiffness indefinite without making it
// singular; the factorization must refuse it whichever CHOLMOD factor form
// (simplicial LDL' or supernodal LL') it chose.
TEST(StructureFactorization, RejectsAnIndefiniteStiffness) {
  Bridge2dOptions o = simple_beam(10.0, 1e9, 1000.0);
  o.bearing_k_N_per_m = 1.0;  // positive to pass the generator's checks...
  auto model = make_bridge_2d(o);
  SparseMatrix K = model->K();
  K.coeffRef(0, 0) -= 1e13;  // ...then a large negative spring on DOF 0
  const StructureModel bad(K, model->M(), model->C(), model->rails(), model->outputs(), model->info());
  EXPECT_THROW(CholmodOperator(bad, EffectiveMatrixFactors{0.0, 0.0, 1.0}, CholmodOperatorOptions{false, 64}),
               InputError);
}

}  // namespace
}  // namespace railvsi

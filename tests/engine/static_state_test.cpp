// The static state of train and structure as the run builds it (the factor
// of K reusing the dynamic operator's ordering, the static flexibility from
// the track substructure) against a direct solve of K u = f(P) by another
// solver (Eigen's simplicial LDL'), the vehicles' equilibrium and the
// contact law, and against the state built without the dynamic operator.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "generators/deck_3d.hpp"
#include "simulation/simulation.hpp"
#include "simulation/static_equilibrium.hpp"
#include "solver/structure_backend.hpp"
#include "solver/structure_coordinates.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

Scene coach_on_deck_3d() {
  Deck3dOptions o;
  o.spans_m = {10.0, 10.0};
  o.mesh = Deck3dMesh{{10, 10}, 4, 2};
  o.approach_m = 30.0;
  o.exit_m = 6.0;
  Scene s;
  s.structure = make_deck_3d(o).model;
  s.train.vehicles.push_back({make_car_2d(testing::ice3_coach()), 0.0});
  s.speed_mps = 50.0;
  s.analysis.dt_s = 2.5e-4;
  s.analysis.contact.law = "hertz";
  s.analysis.contact.rail_lines = {0, 1};
  return s;
}

double max_abs(const Vector& v) { return v.cwiseAbs().maxCoeff(); }

TEST(StaticState, FromTheDynamicOperatorsAnalysisSatisfiesTheStaticEquations) {
  const Scene scene = coach_on_deck_3d();
  const StructureModel& s = *scene.structure;
  const TrainLayout layout(scene.train, scene.analysis.contact);
  const auto dynamic = make_structure_operator(scene);
  // The run's static operator borrows the dynamic one's analysis.
  const auto statics = dynamic->static_operator(s);
  const StructureCoordinates coords(s);
  const Eigen::SimplicialLDLT<SparseMatrix> K(s.K());
  ASSERT_EQ(K.info(), Eigen::Success);
  // The whole coach on the approach (the default start), and straddling the
  // bridge's first support.
  for (const double front_x_m : {default_start_x_m(scene), 12.0}) {
    const StaticState st = static_equilibrium(scene, layout, front_x_m, *statics);
    const auto rows = locate_contacts(s, layout, front_x_m);
    Vector f = Vector::Zero(s.num_dofs());
    add_rail_loads(rows, st.P, 1.0, f, coords);
    const Vector u = K.solve(f);
    // Measured 1.2e-15 (default start) and 2.0e-15 (on the bridge); tolerance 1e-13.
    EXPECT_LT(max_abs(st.u_s - u) / max_abs(u), 1e-13) << front_x_m;

    // The vehicle rests on its wheels: K_v u_v = F_g + E^T P.
    const VehicleModel& v = *layout.vehicles[0].model;
    Vector r = v.K() * st.u_v - layout.gravity_load_N;
    for (std::size_t c = 0; c < layout.contacts.size(); ++c)
      r[layout.contacts[c].global_dof] -= st.P[static_cast<Eigen::Index>(c)];
    EXPECT_LT(max_abs(r) / max_abs(layout.gravity_load_N), 1e-12) << front_x_m;
    // Each wheel is pressed into the rail by the Hertz compression of its load.
    for (std::size_t c = 0; c < layout.contacts.size(); ++c) {
      const auto i = static_cast<Eigen::Index>(c);
      const double delta = rail_top(rows[c], u, coords) - st.u_v[layout.contacts[c].global_dof];
      const double hertz = layout.contacts[c].law->compression(st.P[i]);
      EXPECT_NEAR(delta, hertz, 1e-9 * hertz) << front_x_m << " wheel " << c;
    }
    // The same state from a static operator with an analysis of its own.
    StructureOperatorOptions own_options;
    own_options.rail_flexibility = false;
    const auto own_op = make_structure_operator(scene.structure, {0.0, 0.0, 1.0}, own_options);
    const StaticState own = static_equilibrium(scene, layout, front_x_m, *own_op);
    EXPECT_LT(max_abs(st.u_s - own.u_s) / max_abs(own.u_s), 1e-13) << front_x_m;
    EXPECT_LT(max_abs(st.P - own.P) / max_abs(own.P), 1e-13) << front_x_m;
  }
}

}  // namespace
}  // namespace railvsi

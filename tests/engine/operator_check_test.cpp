// Simulation(scene, op) refuses an operator built for another scene: another
// dt, another HHT alpha, or without the rail flexibility a multibody train
// needs (it would read past an empty index table).
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "simulation/simulation.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

TEST(OperatorCheck, RefusesAnOperatorForAnotherDtAlphaOrWithoutRailFlexibility) {
  const Scene scene = testing::small_viaduct_with_dip(300.0, 0.0);
  EXPECT_NO_THROW(Simulation(scene, make_structure_operator(scene)));

  Scene other_dt = scene;
  other_dt.analysis.dt_s *= 2.0;
  EXPECT_THROW(Simulation(scene, make_structure_operator(other_dt)), InputError);

  Scene other_alpha = scene;
  other_alpha.analysis.hht = HhtParameters::from_alpha(-0.1);
  EXPECT_THROW(Simulation(scene, make_structure_operator(other_alpha)), InputError);

  Scene moving_forces = scene;  // its operator has no rail flexibility
  moving_forces.train.vehicles.clear();
  moving_forces.train.moving_forces = {{0.0, 1e5}};
  EXPECT_THROW(Simulation(scene, make_structure_operator(moving_forces)), InputError);
}

}  // namespace
}  // namespace railvsi

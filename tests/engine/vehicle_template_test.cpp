// The plane car and articulated-set templates against hand-derived facts.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/input_error.hpp"
#include "simulation/static_equilibrium.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// Eigenvalues of K that are zero relative to the largest.
int zero_energy_modes(const VehicleModel& v) {
  Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(v.K());
  const Vector lambda = eig.eigenvalues();
  const double scale = lambda.cwiseAbs().maxCoeff();
  int zero = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) zero += std::abs(lambda[i]) < 1e-9 * scale;
  return zero;
}

TEST(Car2dTemplate, HasTenDofsFourWheelsAndTheTotalMass) {
  const auto car = make_car_2d(testing::ice3_coach());
  EXPECT_EQ(car->num_dofs(), 10);  // body z, theta; 2 bogies z, theta; 4 wheelsets z
  ASSERT_EQ(car->wheels().size(), 4u);
  EXPECT_DOUBLE_EQ(car->total_mass_kg(), 47800.0 + 2 * 3500.0 + 4 * 1800.0);
  EXPECT_DOUBLE_EQ(car->wheels()[3].offset_m, 17.375 + 2.5);
}

// Off the rails the car has four zero-energy modes: bounce and pitch of the
// whole car, and each bogie pitching with its wheelsets about its centre,
// where the single secondary spring sits. On the rails they are restrained.
TEST(Car2dTemplate, FreeVehicleHasFourZeroEnergyModes) {
  const auto car = make_car_2d(testing::ice3_coach());
  EXPECT_EQ(zero_energy_modes(*car), 4);
  const Vector lambda = Eigen::SelfAdjointEigenSolver<DenseMatrix>(car->K()).eigenvalues();
  EXPECT_GT(lambda.minCoeff(), -1e-9 * lambda.cwiseAbs().maxCoeff());
}

TEST(Car2dTemplate, SymmetricCarPutsAQuarterOfItsWeightOnEachWheel) {
  const auto car = make_car_2d(testing::ice3_coach());
  const Vector P = static_wheel_loads_on_rigid_track(*car);
  const double quarter = 62000.0 * kGravity_mps2 / 4.0;
  for (Eigen::Index w = 0; w < P.size(); ++w) EXPECT_NEAR(P[w] / quarter, 1.0, 1e-12);
}

TEST(Car2dTemplate, RejectsNonPositiveStiffnessWithItsPath) {
  Car2dOptions c = testing::ice3_coach();
  c.primary.k_N_per_m = -1.0;
  try {
    make_car_2d(c);
    FAIL() << "negative stiffness accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/primary/k_N_per_m");
  }
}

// Three ICE3-like bodies on four bogies, the two inner ones shared.
Articulated2dOptions three_body_set() { return {testing::ice3_coach(), 3}; }

TEST(Articulated2dTemplate, NBodiesSitOnNPlusOneBogiesWithTheirWheelsAndMass) {
  const auto set = make_articulated_2d(three_body_set());
  // 3 bodies and 4 bogies (bounce, pitch), 8 wheelsets (bounce).
  EXPECT_EQ(set->num_dofs(), 3 * 2 + 4 * 2 + 8);
  ASSERT_EQ(set->wheels().size(), 8u);
  EXPECT_DOUBLE_EQ(set->total_mass_kg(), 3 * 47800.0 + 4 * 3500.0 + 8 * 1800.0);
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_DOUBLE_EQ(set->wheels()[2 * j].offset_m, j * 17.375);
    EXPECT_DOUBLE_EQ(set->wheels()[2 * j + 1].offset_m, j * 17.375 + 2.5);
  }
  EXPECT_EQ(set->body_dofs().size(), 3u) << "every car body is a body of interest";
}

// Each body rests on two points with its centre of mass midway, so each
// end carries half of it whatever the springs; a bogie splits its load
// equally between its two wheelsets.
TEST(Articulated2dTemplate, SharedBogiesCarryHalfOfEachBodyAboveThem) {
  const auto set = make_articulated_2d(three_body_set());
  const Vector P = static_wheel_loads_on_rigid_track(*set);
  const double end_axle_kg = (47800.0 / 2 + 3500.0) / 2 + 1800.0;
  const double shared_axle_kg = (47800.0 + 3500.0) / 2 + 1800.0;
  for (Eigen::Index w = 0; w < P.size(); ++w) {
    const bool end_bogie = w < 2 || w >= 6;
    EXPECT_NEAR(P[w] / kGravity_mps2, end_bogie ? end_axle_kg : shared_axle_kg, 1e-9 * shared_axle_kg) << w;
  }
}

// Off the rails: the heights of the n + 1 joints (each body follows the two
// below it) and the pitch of each bogie about its centre, where all its
// secondary springs sit: 2n + 2 zero-energy modes (4 for a single car).
TEST(Articulated2dTemplate, FreeSetHasTwoNPlusTwoZeroEnergyModes) {
  EXPECT_EQ(zero_energy_modes(*make_articulated_2d(three_body_set())), 2 * 3 + 2);
}

TEST(Articulated2dTemplate, RejectsASingleBodyAndBadValuesWithTheirPaths) {
  Articulated2dOptions one = three_body_set();
  one.bodies = 1;
  Articulated2dOptions light = three_body_set();
  light.car.bogie_mass_kg = 0.0;
  for (const auto& [options, path] : {std::pair{one, "/bodies"}, std::pair{light, "/bogie/mass_kg"}}) {
    try {
      make_articulated_2d(options);
      ADD_FAILURE() << path << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), path);
    }
  }
}

// Wheel, bogie, body, bogie, wheel: four couplings reach every wheel under
// the car body; two only the wheels of the same bogie.
TEST(Car2dTemplate, CoupledDofsReachTheWheelsUnderTheSameCarBody) {
  const auto car = make_car_2d(testing::ice3_coach());
  const auto wheels_reached = [&](int links) {
    const std::vector<int> near = car->coupled_dofs(car->wheels()[0].dof, links);
    std::vector<int> w;
    for (std::size_t i = 0; i < car->wheels().size(); ++i)
      if (std::find(near.begin(), near.end(), car->wheels()[i].dof) != near.end()) w.push_back(static_cast<int>(i));
    return w;
  };
  EXPECT_EQ(wheels_reached(4), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(wheels_reached(2), (std::vector<int>{0, 1}));
  EXPECT_EQ(wheels_reached(0), (std::vector<int>{0}));
}

// On an articulated set, the first body's wheels (bogies 1 and 2) are
// within four couplings of the front wheel; bogie 3, under the second and
// third bodies only, is not.
TEST(Articulated2dTemplate, CoupledDofsStopAtTheFirstCarBody) {
  const auto set = make_articulated_2d(three_body_set());
  ASSERT_EQ(set->wheels().size(), 8u);  // 4 bogies x 2 axles
  const std::vector<int> near = set->coupled_dofs(set->wheels()[0].dof, 4);
  for (std::size_t i = 0; i < set->wheels().size(); ++i) {
    const bool reached = std::find(near.begin(), near.end(), set->wheels()[i].dof) != near.end();
    EXPECT_EQ(reached, i < 4) << "wheel " << i;
  }
}

}  // namespace
}  // namespace railvsi

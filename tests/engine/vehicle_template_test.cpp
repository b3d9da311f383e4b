// The plane car template against hand-derived facts.
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "simulation/static_equilibrium.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

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
  Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(car->K());
  const Vector lambda = eig.eigenvalues();
  const double scale = lambda.cwiseAbs().maxCoeff();
  int zero = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) zero += std::abs(lambda[i]) < 1e-9 * scale;
  EXPECT_EQ(zero, 4);
  EXPECT_GT(lambda.minCoeff(), -1e-9 * scale);
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

}  // namespace
}  // namespace railvsi

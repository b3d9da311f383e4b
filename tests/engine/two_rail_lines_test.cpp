// A plane train on a structure with two rail lines (the 3D import case):
// each wheelset bears on both rails. Two identical, uncoupled beams under a
// wheelset are the same system as one beam of twice the stiffness and mass
// under the lumped wheelset, so the two scenes must give the same response.
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "simulation/simulation.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

Bridge2dOptions beam(double EI, double m) {
  Bridge2dOptions o;
  o.spans_m = {20.0};
  o.deck_EI_Nm2 = EI;
  o.deck_mass_kg_per_m = m;
  o.damping_ratio = 0.02;
  o.element_length_m = 1.0;
  return o;
}

// Two copies of a model side by side, uncoupled; rail line i on copy i.
std::shared_ptr<const StructureModel> twin(const StructureModel& one) {
  const int n = one.num_dofs();
  const auto stack = [n](const SparseMatrix& A) {
    std::vector<Triplet> t;
    for (int k = 0; k < A.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
        t.emplace_back(it.row(), it.col(), it.value());
        t.emplace_back(it.row() + n, it.col() + n, it.value());
      }
    SparseMatrix B(2 * n, 2 * n);
    B.setFromTriplets(t.begin(), t.end());
    return B;
  };
  RailLine second = one.rails().front();
  for (auto& e : second.element_dofs)
    for (int& d : e)
      if (d >= 0) d += n;
  std::vector<RailLine> rails{one.rails().front(), second};
  return std::make_shared<const StructureModel>(stack(one.K()), stack(one.M()), stack(one.C()), rails,
                                                one.outputs(), one.info());
}

Scene scene_on(std::shared_ptr<const StructureModel> s, std::vector<int> rails) {
  Scene sc;
  sc.structure = std::move(s);
  sc.train.vehicles.push_back({make_car_2d(testing::ice3_coach()), 0.0});
  sc.speed_mps = 250.0 / 3.6;
  sc.analysis.dt_s = 5e-4;
  sc.analysis.duration_s = 0.6;
  sc.analysis.contact.rail_lines = std::move(rails);
  return sc;
}

TEST(TwoRailLines, WheelsetOnTwinBeamsEqualsLumpedWheelsetOnDoubleBeam) {
  const double EI = 2.0e10, m = 8000.0;
  const Result twin_run = Simulation(scene_on(twin(*make_bridge_2d(beam(EI, m))), {0, 1})).run();
  const Result lumped_run = Simulation(scene_on(make_bridge_2d(beam(2.0 * EI, 2.0 * m)), {0})).run();
  ASSERT_TRUE(twin_run.status.ok()) << twin_run.status.message();
  ASSERT_TRUE(lumped_run.status.ok()) << lumped_run.status.message();
  ASSERT_EQ(twin_run.histories.contact_force_N.size(), 8u);  // 4 wheelsets x 2 rails
  ASSERT_EQ(lumped_run.histories.contact_force_N.size(), 4u);
  // Same deck response (the output DOF is on the first beam) ...
  EXPECT_LT(testing::relative_history_difference(twin_run.histories.deck_displacement_m,
                                                 lumped_run.histories.deck_displacement_m), 1e-9);
  // ... and each rail carries half of the lumped wheelset's force.
  for (std::size_t w = 0; w < 4; ++w)
    for (std::size_t r = 0; r < 2; ++r) {
      const auto& half = twin_run.histories.contact_force_N[2 * w + r];
      const auto& whole = lumped_run.histories.contact_force_N[w];
      for (std::size_t k = 0; k < whole.size(); ++k) EXPECT_NEAR(2.0 * half[k], whole[k], 1e-6 * whole[0]);
    }
  EXPECT_EQ(twin_run.histories.wheel_names[1], "v1_w1_r2");
}

TEST(TwoRailLines, MovingForceIsSplitEquallyBetweenTheRails) {
  const double EI = 2.0e10, m = 8000.0;
  Scene twin_scene = scene_on(twin(*make_bridge_2d(beam(EI, m))), {0, 1});
  Scene lumped_scene = scene_on(make_bridge_2d(beam(2.0 * EI, 2.0 * m)), {0});
  for (Scene* s : {&twin_scene, &lumped_scene}) {
    s->train.vehicles.clear();
    s->train.moving_forces = {{0.0, 170e3}, {3.0, 170e3}};
  }
  const Result a = Simulation(twin_scene).run();
  const Result b = Simulation(lumped_scene).run();
  ASSERT_TRUE(a.status.ok() && b.status.ok());
  EXPECT_LT(testing::relative_history_difference(a.histories.deck_displacement_m, b.histories.deck_displacement_m), 1e-9);
}

TEST(TwoRailLines, RejectsARailLineTheStructureDoesNotHave) {
  Scene s = scene_on(make_bridge_2d(beam(2e10, 8000.0)), {0, 1});
  EXPECT_THROW(Simulation{s}, InputError);
}

}  // namespace
}  // namespace railvsi

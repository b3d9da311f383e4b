// The run's discrete energy balance (simulation/energy_balance.hpp): closes
// to round-off for the trapezoidal rule without damping, and with HHT
// dissipation and damping once E_HHT is counted; the HHT term is what
// alpha < 0 removes.
#include <gtest/gtest.h>

#include <cmath>

#include "simulation/energy_balance.hpp"
#include "simulation/simulation.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

Scene beam_under_a_force(double alpha, double damping) {
  Bridge2dOptions b;
  b.spans_m = {15.0};
  b.deck_EI_Nm2 = 1.5e10;
  b.deck_mass_kg_per_m = 15000;
  b.damping_ratio = damping;
  b.element_length_m = 0.75;
  Scene s;
  s.structure = make_bridge_2d(b);
  s.train.moving_forces = {{0.0, 2e5}, {3.0, 2e5}};
  s.speed_mps = 60.0;
  s.analysis.dt_s = 5e-4;
  s.analysis.hht = HhtParameters::from_alpha(alpha);
  s.analysis.extra_time_s = 1.0;
  return s;
}

// The balance holds in the coordinates the backend integrates: the model's
// DOFs, or the modes (M = I, C and K diagonal).
class EnergyBalanceOfBackend : public ::testing::TestWithParam<StructureBackend> {
 protected:
  Scene scene(double alpha, double damping) const {
    Scene s = beam_under_a_force(alpha, damping);
    s.analysis.structure_backend = GetParam();
    if (GetParam() == StructureBackend::kModal) s.analysis.modal_modes = 10;
    return s;
  }
};

TEST_P(EnergyBalanceOfBackend, TrapezoidalRuleWithoutDampingConservesToRoundOff) {
  const Result r = Simulation(scene(0.0, 0.0)).run();
  ASSERT_TRUE(r.status.ok());
  EXPECT_LE(r.summary.energy_residual, 1e-11);  // measured about 1e-13
}

TEST_P(EnergyBalanceOfBackend, HhtDissipationAndDampingAreAccounted) {
  for (double alpha : {-0.05, -0.3}) {
    const Result r = Simulation(scene(alpha, 0.02)).run();
    ASSERT_TRUE(r.status.ok());
    EXPECT_LE(r.summary.energy_residual, 1e-11) << alpha;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, EnergyBalanceOfBackend,
                         ::testing::Values(StructureBackend::kFiniteElements, StructureBackend::kModal),
                         [](const ::testing::TestParamInfo<StructureBackend>& info) {
                           return std::string(structure_backend_name(info.param));
                         });

// A single oscillator stepped by hand: the HHT term accumulates the energy
// alpha < 0 removes, T + U falls by exactly that much.
TEST(EnergyBalance, HhtTermIsTheEnergyTheSchemeRemoves) {
  const HhtCoefficients h(HhtParameters::from_alpha(-0.3), 0.2);  // 5 steps per period of omega = 2 pi
  DenseMatrix M(1, 1), C(1, 1), K(1, 1);
  M << 1.0;
  C << 0.0;
  K << 4.0 * M_PI * M_PI;
  KinematicState s;
  s.resize(1);
  s.u[0] = 1.0;
  s.a[0] = -K(0, 0);
  const Vector f = Vector::Zero(1);
  EnergyAccount<DenseMatrix> e(M, C, K, s, f);
  for (int n = 0; n < 50; ++n) {
    // K_bar u_{n+1} = history: the same equations RunState solves.
    Vector rhs(1), work(1);
    hht_history_rhs(h, M, C, K, s, rhs, work);
    const double kbar = h.c0 * M(0, 0) + (1.0 + h.alpha) * K(0, 0);
    const KinematicState old = s;
    Vector u_new(1);
    u_new[0] = rhs[0] / kbar;
    hht_update(h, u_new, s);
    e.step(h, old, s, f);
  }
  const EnergyTotals& t = e.totals();
  const double lost = e.initial_mechanical_J() - t.kinetic_J - t.strain_J;
  EXPECT_GT(lost, 0.5 * e.initial_mechanical_J());  // strongly damped at 5 steps per period
  EXPECT_NEAR(t.hht_J, lost, 1e-12 * e.initial_mechanical_J());
}

}  // namespace
}  // namespace railvsi

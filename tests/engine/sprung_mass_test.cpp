// Sprung mass crossing a simply supported beam (Biggs, Introduction to
// Structural Dynamics, 1964; Yang & Wu 2001, Eng. Struct. 23, 452-469): the engine's interaction run
// (FE deck, HHT, rigid bilateral contact) against an independent modal
// integration of the beam and the sprung mass written here (classical RK4).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "generators/bridge_2d.hpp"
#include "model/vehicle_model.hpp"
#include "simulation/simulation.hpp"
#include "../support/worst_of.hpp"

namespace railvsi {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = kGravity_mps2;  // the engine's gravity; an input of both models

// Biggs' data (Biggs 1964, as used by Yang & Wu 2001).
constexpr double kL = 25.0;
constexpr double kEI = 2.87e9 * 2.90;
constexpr double kMass = 2303.0;    // kg/m
constexpr double kMv = 5750.0;      // kg
constexpr double kKv = 1595.0e3;    // N/m
constexpr double kSpeed = 100.0 / 3.6;

double beam_omega(int j) { return j * j * kPi * kPi / (kL * kL) * std::sqrt(kEI / kMass); }

struct ModalHistory {
  std::vector<double> midspan_m;     // positive up
  std::vector<double> body_acc_mps2;
  std::vector<double> contact_N;     // compressive wheel load
};

// Independent reference: N beam modes sin(j pi x / L) (modal mass m L / 2)
// and the sprung mass z, joined through the spring to a massless contact
// point that follows the beam (rigid contact):
//   P = kv (w(vt) - z),  Mv z'' = P - Mv g,
//   q_j'' = -w_j^2 q_j - 2/(m L) P sin(j pi v t / L).
// Starts from static equilibrium with the mass over the left support: beam
// at rest and undeflected, z = -Mv g / kv. Classical RK4 with a fixed step h;
// results sampled every `stride` steps.
ModalHistory modal_reference(int modes, double kv, double h, int steps, int stride) {
  const int n = 2 * modes + 2;
  using State = std::vector<double>;
  const auto rhs = [&](double t, const State& y, State& dy) {
    const double x = kSpeed * t;
    double w = 0.0;
    for (int j = 0; j < modes; ++j) w += y[j] * std::sin((j + 1) * kPi * x / kL);
    const double z = y[2 * modes];
    const double P = kv * (w - z);
    for (int j = 0; j < modes; ++j) {
      dy[j] = y[modes + j];
      const double wj = beam_omega(j + 1);
      dy[modes + j] = -wj * wj * y[j] - 2.0 / (kMass * kL) * P * std::sin((j + 1) * kPi * x / kL);
    }
    dy[2 * modes] = y[2 * modes + 1];
    dy[2 * modes + 1] = P / kMv - kG;
  };
  const auto sample = [&](double t, const State& y, ModalHistory& out) {
    double w_mid = 0.0, w_load = 0.0;
    for (int j = 0; j < modes; ++j) {
      w_mid += y[j] * std::sin((j + 1) * kPi / 2.0);
      w_load += y[j] * std::sin((j + 1) * kPi * kSpeed * t / kL);
    }
    const double P = kv * (w_load - y[2 * modes]);
    out.midspan_m.push_back(w_mid);
    out.body_acc_mps2.push_back(P / kMv - kG);
    out.contact_N.push_back(P);
  };
  State y(n, 0.0), k1(n), k2(n), k3(n), k4(n), tmp(n);
  y[2 * modes] = -kMv * kG / kv;
  ModalHistory out;
  sample(0.0, y, out);
  for (int s = 0; s < steps; ++s) {
    const double t = s * h;
    rhs(t, y, k1);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    rhs(t + 0.5 * h, tmp, k2);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    rhs(t + 0.5 * h, tmp, k3);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * k3[i];
    rhs(t + h, tmp, k4);
    for (int i = 0; i < n; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    if ((s + 1) % stride == 0) sample((s + 1) * h, y, out);
  }
  return out;
}

// The Biggs vehicle as imported matrices: DOF 0 the sprung mass, DOF 1 the
// contact point (massless, as in Biggs), a spring kv between them.
std::shared_ptr<const VehicleModel> biggs_vehicle(double kv) {
  DenseMatrix K(2, 2), M = DenseMatrix::Zero(2, 2);
  K << kv, -kv, -kv, kv;
  M(0, 0) = kMv;
  Vector gravity(2);
  gravity << 1.0, 1.0;  // both translational; the wheel's gravity load is 0 (mass 0)
  Wheel wheel;
  wheel.dof = 1;
  wheel.offset_m = 0.0;
  return std::make_shared<const VehicleModel>("biggs", K, M, DenseMatrix::Zero(2, 2), gravity,
                                              std::vector<Wheel>{wheel});
}

Scene biggs_scene(double kv, double dt, double alpha) {
  Bridge2dOptions o;
  o.spans_m = {kL};
  o.deck_EI_Nm2 = kEI;
  o.deck_mass_kg_per_m = kMass;
  o.damping_ratio = 0.0;  // Biggs' beam is undamped
  o.element_length_m = 0.5;
  Scene scene;
  scene.structure = make_bridge_2d(o);
  scene.train.vehicles = {{biggs_vehicle(kv), 0.0}};
  scene.speed_mps = kSpeed;
  scene.start_x_m = 0.0;  // the wheel on the left support
  scene.analysis.dt_s = dt;
  scene.analysis.hht = HhtParameters::from_alpha(alpha);
  scene.analysis.contact.law = "rigid";
  scene.analysis.contact.unilateral = false;
  scene.analysis.duration_s = kL / kSpeed;
  return scene;
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = railvsi::testing::worst_of(m, std::abs(v));
  return m;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = railvsi::testing::worst_of(m, std::abs(a[k] - b[k]));
  return m;
}

// Crossing time 0.9 s: 9000 engine steps of 1e-4 s (>= 2000 per period of
// the beam's first mode, 4.78 Hz, and of the vehicle, 2.65 Hz); the RK4
// reference takes 10 steps of 1e-5 s per engine step (RK4 error per period
// of mode 20, w h ~ 0.12, ~1e-6: far below the tolerance).
constexpr int kEngineSteps = 9000;
constexpr int kRefPerEngineStep = 10;
constexpr int kModes = 20;

// HHT alpha, and the structure backend: finite elements, or the modal
// backend with the reference's 20 modes (the same HHT on each mode).
struct BiggsCase {
  double alpha;
  StructureBackend backend;
};

class BiggsSprungMass : public ::testing::TestWithParam<BiggsCase> {};

TEST_P(BiggsSprungMass, MidspanDeflectionAndBodyAccelerationMatchModalIntegration) {
  const double alpha = GetParam().alpha;
  const double T = kL / kSpeed, dt = T / kEngineSteps;
  Scene scene = biggs_scene(kKv, dt, alpha);
  scene.analysis.structure_backend = GetParam().backend;
  scene.analysis.modal_modes = GetParam().backend == StructureBackend::kModal ? kModes : 0;
  const Result r = Simulation(scene).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const Histories& hist = r.histories;
  ASSERT_EQ(hist.t_s.size(), static_cast<std::size_t>(kEngineSteps) + 1);
  ASSERT_EQ(hist.point_names.at(0), "span1_mid");
  ASSERT_EQ(hist.carbody_acceleration_mps2.size(), 1u);  // DOF 0, the only non-wheel DOF
  // Static start: the whole weight on the wheel.
  ASSERT_EQ(r.summary.static_wheel_load_N.size(), 1u);
  EXPECT_NEAR(r.summary.static_wheel_load_N[0], kMv * kG, 1e-9 * kMv * kG);

  const ModalHistory ref = modal_reference(kModes, kKv, dt / kRefPerEngineStep,
                                           kEngineSteps * kRefPerEngineStep, kRefPerEngineStep);
  ASSERT_EQ(ref.midspan_m.size(), hist.t_s.size());

  const auto& u = hist.deck_displacement_m.at(0);
  const auto& a = hist.carbody_acceleration_mps2.at(0);
  const auto& P = hist.contact_force_N.at(0);
  const double du = max_abs_diff(u, ref.midspan_m) / max_abs(ref.midspan_m);
  const double da = max_abs_diff(a, ref.body_acc_mps2) / max_abs(ref.body_acc_mps2);
  const double dP = max_abs_diff(P, ref.contact_N) / max_abs(ref.contact_N);
  std::printf("[biggs] hht alpha=%.2f: max |w_mid| ref=%.6e engine=%.6e, rel diff %.3e; "
              "max |body acc| ref=%.6e engine=%.6e, rel diff %.3e; contact force rel diff %.3e\n",
              alpha, max_abs(ref.midspan_m), max_abs(u), du, max_abs(ref.body_acc_mps2), max_abs(a), da, dP);
  // Max abs difference over the crossing relative to the reference's max
  // abs value. Measured over the four cases (FE and modal, alpha 0 and
  // -0.05; 2026-11-27): deflection 3.45e-5, body acceleration 2.52e-4,
  // contact force 2.87e-6; tolerances about 3x: 1e-4, 7.5e-4, 8.5e-6.
  EXPECT_LT(du, 1e-4);
  EXPECT_LT(da, 7.5e-4);
  EXPECT_LT(dP, 8.5e-6);
  // Interaction on the modes says that its error is not known in general;
  // on the FE structure there is no such warning.
  const bool modal = GetParam().backend == StructureBackend::kModal;
  const auto unverified = std::count_if(r.summary.warnings.begin(), r.summary.warnings.end(), [](const RunWarning& w) {
    return w.code == "modal_interaction_unverified";
  });
  EXPECT_EQ(unverified, modal ? 1 : 0);
}

INSTANTIATE_TEST_SUITE_P(HhtAlphaAndBackend, BiggsSprungMass,
                         ::testing::Values(BiggsCase{0.0, StructureBackend::kFiniteElements},
                                           BiggsCase{-0.05, StructureBackend::kFiniteElements},
                                           BiggsCase{0.0, StructureBackend::kModal},
                                           BiggsCase{-0.05, StructureBackend::kModal}),
                         [](const ::testing::TestParamInfo<BiggsCase>& info) {
                           return std::string(info.param.alpha == 0.0 ? "alpha0_" : "alpha_minus0p05_") +
                                  structure_backend_name(info.param.backend);
                         });

// Frýba's undamped series for a constant force P (downward) entering at
// x = 0 at t = 0 (Fryba 1972, section 1.3), deflection positive up at x, for t <= L/v.
double fryba_midspan_up(double P, double t, int modes) {
  const double w1 = beam_omega(1), a = kSpeed * kPi / (kL * w1);
  const double v0 = 2.0 * P * std::pow(kL, 3) / (std::pow(kPi, 4) * kEI);
  const double om = kPi * kSpeed / kL;
  double w = 0.0;
  for (int j = 1; j <= modes; ++j) {
    // alpha = 0.116 for Biggs' beam at 100 km/h: no resonant term.
    w += v0 / (j * j * (j * j - a * a)) * (std::sin(j * om * t) - a / j * std::sin(j * j * w1 * t)) *
         std::sin(j * kPi / 2.0);
  }
  return -w;
}

TEST(BiggsSprungMassLimit, VerySoftSuspensionTendsToMovingForceOfTheVehicleWeight) {
  // kv -> kv/1000 (vehicle at 0.084 Hz, 12 s period against a 0.9 s crossing):
  // the spring force stays Mv g to ~1e-3 relative (Mv g / kv = 35 m of
  // static compression), so the beam sees a constant moving force.
  const double T = kL / kSpeed, dt = T / kEngineSteps;
  const Scene scene = biggs_scene(1e-3 * kKv, dt, 0.0);
  const Result r = Simulation(scene).run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  const auto& t = r.histories.t_s;
  const auto& u = r.histories.deck_displacement_m.at(0);
  std::vector<double> ref(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) ref[k] = fryba_midspan_up(kMv * kG, t[k], 60);
  const double diff = max_abs_diff(u, ref) / max_abs(ref);
  const double peak = max_abs(u) / max_abs(ref) - 1.0;
  const double force = max_abs_diff(r.histories.contact_force_N.at(0),
                                    std::vector<double>(t.size(), kMv * kG)) / (kMv * kG);
  std::printf("[biggs soft] max |w_mid| series=%.6e engine=%.6e (rel %.3e), history diff/peak %.3e, "
              "max |P - Mv g|/(Mv g) %.3e\n",
              max_abs(ref), max_abs(u), peak, diff, force);
  // Measured 9.05e-5 (history) and 6.62e-5 (force) of the reference's max
  // abs value over the crossing (2026-11-27); tolerances 2.7e-4 and 1.9e-4.
  EXPECT_LT(diff, 2.7e-4);
  EXPECT_LT(force, 1.9e-4);
}

}  // namespace
}  // namespace railvsi

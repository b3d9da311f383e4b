// The 3D deck generator: mesh size against the requested DOFs, symmetric
// matrices with K positive definite after the supports, and a span against
// Timoshenko beam theory written out here (static deflection under self
// weight and under an axle load on the rails, first bending frequency).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/input_error.hpp"
#include "generators/deck_3d.hpp"
#include "solver/cholmod_operator.hpp"

namespace railvsi {
namespace {

// One model of ~20,000 DOFs for the tests that need a built deck: rails at
// 0.5 m with short approaches, so that a rail node sits over each midspan
// and the DOFs go to the deck (mesh 40 x 12 x 3 per span).
const Deck3dOptions& options_20k() {
  static const Deck3dOptions o = [] {
    Deck3dOptions d;
    d.target_dofs = 20000;
    d.sleeper_spacing_m = 0.5;
    d.approach_m = 10.0;
    d.exit_m = 10.0;
    return d;
  }();
  return o;
}

const Deck3d& deck_20k() {
  static const Deck3d d = make_deck_3d(options_20k());
  return d;
}

// Section properties and Timoshenko's shear coefficient of the rectangle (Cowper).
struct Beam {
  double EI, kGA, rhoA, rhoI;
};
Beam beam_of(const Deck3dOptions& o) {
  const double A = o.width_m * o.depth_m, I = o.width_m * std::pow(o.depth_m, 3) / 12.0;
  const double G = o.E_Pa / (2.0 * (1.0 + o.poisson)), kappa = 10.0 * (1.0 + o.poisson) / (12.0 + 11.0 * o.poisson);
  return {o.E_Pa * I, kappa * G * A, o.density_kg_per_m3 * A, o.density_kg_per_m3 * I};
}

// Mean vertical displacement of the deck nodes of the cross-section at x.
double section_mean_w(const Deck3d& d, const Vector& u, double x_m) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < d.node_m.size(); ++i)
    if (std::abs(d.node_m[i][0] - x_m) < 1e-9 && d.node_dofs[i][2] >= 0) {
      sum += u[d.node_dofs[i][2]];
      ++count;
    }
  EXPECT_GT(count, 0) << "no deck nodes at x = " << x_m;
  return sum / count;
}

double max_abs_asymmetry(const SparseMatrix& A) {
  const SparseMatrix D = SparseMatrix(A.transpose()) - A;
  return D.nonZeros() == 0 ? 0.0 : D.coeffs().abs().maxCoeff();
}

TEST(Deck3d, MeshHitsTheRequestedDofsWithinFivePercent) {
  for (const int target : {5000, 20000, 50000, 230000}) {
    Deck3dOptions o;
    o.target_dofs = target;
    const Deck3dMesh mesh = choose_deck_3d_mesh(o);
    EXPECT_NEAR(static_cast<double>(deck_3d_dofs(o, mesh)), target, 0.05 * target) << target;
  }
  // The count is the built model's (230,000 is built by the seed-scale benchmark).
  for (const int target : {5000, 20000}) {
    Deck3dOptions o;
    o.target_dofs = target;
    const Deck3d d = make_deck_3d(o);
    EXPECT_EQ(d.model->num_dofs(), deck_3d_dofs(o, d.mesh));
    EXPECT_NEAR(d.model->num_dofs(), target, 0.05 * target);
  }
}

TEST(Deck3d, RejectsATargetTheRailsAloneExceed) {
  Deck3dOptions o;
  o.target_dofs = 3000;  // the rails over 400 m of approach have 3,436
  EXPECT_THROW(choose_deck_3d_mesh(o), InputError);
  o.approach_m = 20.0;
  EXPECT_NEAR(static_cast<double>(deck_3d_dofs(o, choose_deck_3d_mesh(o))), 3000.0, 150.0);
}

TEST(Deck3d, MatricesAreSymmetricAndStiffnessIsPositiveDefiniteAfterSupports) {
  const StructureModel& s = *deck_20k().model;
  for (const SparseMatrix* A : {&s.K(), &s.M(), &s.C()})
    EXPECT_LE(max_abs_asymmetry(*A), 1e-12 * A->coeffs().abs().maxCoeff());
  EXPECT_GT(s.M().diagonal().minCoeff(), 0.0) << "every free DOF carries mass";
  // CHOLMOD refuses a matrix with a non-positive pivot (InputError).
  EXPECT_NO_THROW(CholmodOperator(s, EffectiveMatrixFactors{0.0, 0.0, 1.0}, {.rail_flexibility = false}));
  EXPECT_EQ(s.rails().size(), 2u);
}

TEST(Deck3d, SelfWeightDeflectionOfASpanMatchesTimoshenkoBeamTheory) {
  const Deck3d& d = deck_20k();
  const Deck3dOptions& o = options_20k();
  const CholmodOperator op(*d.model, EffectiveMatrixFactors{0.0, 0.0, 1.0}, {.rail_flexibility = false});
  Vector f = Vector::Zero(d.model->num_dofs()), u;
  for (const auto& dofs : d.node_dofs)
    if (dofs[2] >= 0) f[dofs[2]] = -kGravity_mps2 * d.model->M().coeff(dofs[2], dofs[2]);
  auto ws = op.make_workspace();
  ASSERT_TRUE(op.solve(f, u, *ws).ok());
  const Beam b = beam_of(o);
  const double L = 25.0, q = b.rhoA * kGravity_mps2;
  const double expected = -(5.0 * q * std::pow(L, 4) / (384.0 * b.EI) + q * L * L / (8.0 * b.kGA));
  // Measured -0.4 % (mesh 40 x 12 x 3 per span): discretization and the
  // 3D supports (along the soffit edge, not at the beam axis).
  EXPECT_NEAR(section_mean_w(d, u, 37.5) / expected, 1.0, 0.01);
}

TEST(Deck3d, AxleLoadOnBothRailsDeflectsTheSpanLikeAPointLoad) {
  const Deck3d& d = deck_20k();
  const StructureModel& s = *d.model;
  const CholmodOperator op(s, EffectiveMatrixFactors{0.0, 0.0, 1.0}, {.rail_flexibility = false});
  const double P = 170e3, L = 25.0, x_mid = 12.5;
  Vector f = Vector::Zero(s.num_dofs()), u;
  for (const RailLine& rail : s.rails()) {
    const auto row = rail.locate(x_mid);
    ASSERT_TRUE(row);
    for (int k = 0; k < 4; ++k)
      if (row->dof[k] >= 0) f[row->dof[k]] -= 0.5 * P * row->weight[k];
  }
  auto ws = op.make_workspace();
  ASSERT_TRUE(op.solve(f, u, *ws).ok());
  const Beam b = beam_of(options_20k());
  const double expected = -(P * std::pow(L, 3) / (48.0 * b.EI) + P * L / (4.0 * b.kGA));
  // Measured -1.1 %: the rail spreads the load over a few pads (its elastic
  // length on the pads, (4 EI / (k / spacing))^(1/4), is 0.8 m), which
  // lowers the midspan deflection, and the section mean includes the nodes
  // under the pads.
  EXPECT_NEAR(section_mean_w(d, u, x_mid) / expected, 1.0, 0.02);
}

TEST(Deck3d, FirstBendingFrequencyMatchesTimoshenkoBeamTheory) {
  const Deck3d& d = deck_20k();
  const StructureModel& s = *d.model;
  const CholmodOperator op(s, EffectiveMatrixFactors{0.0, 0.0, 1.0}, {.rail_flexibility = false});
  auto ws = op.make_workspace();
  // Inverse iteration from the self-weight shape: the three spans' first
  // bending modes (nearly equal: the rails couple them) are far below the
  // next modes (about 17 Hz), so a few iterations converge.
  Vector u = Vector::Zero(s.num_dofs()), next;
  for (const auto& dofs : d.node_dofs)
    if (dofs[2] >= 0) u[dofs[2]] = 1.0;
  for (int it = 0; it < 6; ++it) {
    ASSERT_TRUE(op.solve(Vector(s.M() * u), next, *ws).ok());
    u = next / next.norm();
  }
  const double f_model = std::sqrt(u.dot(s.K() * u) / u.dot(s.M() * u)) / (2.0 * std::numbers::pi);
  // Simply supported Timoshenko beam, mode 1: det [kGA k^2 - m w^2, -kGA k;
  // -kGA k, EI k^2 + kGA - J w^2] = 0 with k = pi/L; m includes both rails.
  const Deck3dOptions& o = options_20k();
  const Beam b = beam_of(o);
  const double k = std::numbers::pi / 25.0, m = b.rhoA + 2.0 * o.rail_mass_kg_per_m, J = b.rhoI;
  const double qa = m * J, qb = -(m * (b.EI * k * k + b.kGA) + J * b.kGA * k * k), qc = b.kGA * k * k * b.EI * k * k;
  const double w2_timoshenko = (-qb - std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
  // The bearings are at the soffit, e = depth/2 below the beam axis, and the
  // fixed one holds the span there: an end rotation theta0 = k W moves the
  // whole deck along x by e * theta0. With the mode W sin(kx), Rayleigh's
  // quotient gains the kinetic energy rhoA L (e k W)^2 / 2 over the bending
  // one m L W^2 / 4: w^2 divides by 1 + 2 (rhoA / m) (e k)^2 (2 % here).
  const double e = 0.5 * o.depth_m;
  const double w2 = w2_timoshenko / (1.0 + 2.0 * (b.rhoA / m) * std::pow(e * k, 2));
  const double f_beam = std::sqrt(w2) / (2.0 * std::numbers::pi);
  // Measured +0.05 %.
  EXPECT_NEAR(f_model / f_beam, 1.0, 0.005) << f_model << " Hz against " << f_beam << " Hz";
}

}  // namespace
}  // namespace railvsi

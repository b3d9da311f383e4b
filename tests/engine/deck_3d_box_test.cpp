// The box-girder section of the 3D deck generator against beam theory,
// written out here: the section's area, second moment and Bredt torsion
// constant from the plate dimensions, the first vertical bending frequency
// of a simply supported span (Euler-Bernoulli, and Timoshenko with the
// bearing offset) and its first torsion frequency (St Venant), each mode
// found by its shape at midspan, not by its index; and both frequencies
// against a separately written model of the same structure (20-node
// bricks, tests/engine/reference/box_girder_reference.py).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "core/input_error.hpp"
#include "generators/deck_3d.hpp"
#include "solver/modal_analysis.hpp"

namespace railvsi {
namespace {

constexpr double kSpan_m = 25.0;

// The default box: 7 m top slab 0.3 m thick, 5 m bottom slab 0.25 m thick,
// webs 0.4 m, 2 m deep. One span, short approaches; 50 x 16 x 6 grid
// (one element through each slab and web: the hexahedron has Wilson's
// incompatible modes, which bend without locking), 11,543 DOFs.
Deck3dOptions box_options() {
  Deck3dOptions o;
  o.box = BoxGirderSection{};
  o.spans_m = {kSpan_m};
  o.sleeper_spacing_m = 0.5;
  o.approach_m = 2.0;
  o.exit_m = 2.0;
  o.mesh = Deck3dMesh{{50}, 16, 6};
  return o;
}

// The independent reference: tests/engine/reference/box_girder_reference.py,
// written from deck_3d's specification (plates, diaphragms, bearings, rails
// on pads), not its code: 20-node serendipity bricks, 3 x 3 x 3 Gauss,
// consistent mass, half the section by symmetry; run 2026-11-27. Level 1
// (elements about 1 m along x, 2 across the half void, 1 through each
// plate, 2 up the web; 11,609 DOFs over the two halves) has the product's
// element size at the bearings (0.5 m along x, the bottom slab in one).
// Its own error estimate, level 1 against level 2 (every count doubled):
// bending -0.40 %, torsion -1.9 % (-0.46 % and -0.86 % with the
// diaphragms), in torsion almost all from the section's discretisation (a
// bearing patch shows the same -1.7 %). Beyond that the bearings matter: the bearing (w = 0 on the soffit edge line, v and u at a
// node) is singular in a 3D solid, so neither code has a mesh-converged
// torsion frequency - both lose about 1 % each time the elements at the
// bearing are halved (reference levels 1, 2, 3: 19.430, 19.063, 18.688 Hz;
// with a finite bearing patch the reference converges). At the same
// element size at the bearing the codes agree within about 1 % (also at
// 0.25 m: 19.197 Hz against 19.035); docs/verification.md has the study.
// ctest box_girder_reference_reproduces re-runs level 1 and checks these
// numbers.
struct ReferenceHz {
  double bending, torsion;
};
constexpr ReferenceHz kReferenceLevel1{6.4818, 19.4303};            // box_options()
constexpr ReferenceHz kReferenceLevel1Diaphragms{6.2085, 22.8244};  // with 3 intermediate diaphragms
// --generator-nx 100: the diaphragms of a 100-element span (0.25 m), and so
// elements of 0.25 m at the bearings.
constexpr ReferenceHz kReferenceLevel1Nx100{6.4502, 19.0347};

// The section written out differently from the generator: the outer
// rectangle of the box below the top slab, less the void, plus the top slab.
struct Section {
  double A, zc, I, I_lateral, J;
};
Section hand_section(const BoxGirderSection& b) {
  const double h = b.depth_m - b.top_thickness_m;             // below the top slab
  const double vw = b.bottom_width_m - 2.0 * b.web_thickness_m;  // void width
  const double vh = h - b.bottom_thickness_m;                 // void height
  const double A_top = b.top_width_m * b.top_thickness_m, A_out = b.bottom_width_m * h, A_void = vw * vh;
  const double z_top = b.depth_m - 0.5 * b.top_thickness_m, z_out = 0.5 * h, z_void = b.bottom_thickness_m + 0.5 * vh;
  Section s{};
  s.A = A_top + A_out - A_void;
  s.zc = (A_top * z_top + A_out * z_out - A_void * z_void) / s.A;
  s.I = b.top_width_m * std::pow(b.top_thickness_m, 3) / 12.0 + A_top * std::pow(z_top - s.zc, 2) +
        b.bottom_width_m * std::pow(h, 3) / 12.0 + A_out * std::pow(z_out - s.zc, 2) -
        (vw * std::pow(vh, 3) / 12.0 + A_void * std::pow(z_void - s.zc, 2));
  s.I_lateral = b.top_thickness_m * std::pow(b.top_width_m, 3) / 12.0 + h * std::pow(b.bottom_width_m, 3) / 12.0 -
                vh * std::pow(vw, 3) / 12.0;
  // Bredt (Timoshenko & Goodier, Theory of Elasticity, section 115): a
  // rectangle of mid-lines, a = 4.6 m wide and d = 1.725 m high for the default.
  const double a = b.bottom_width_m - b.web_thickness_m;
  const double d = b.depth_m - 0.5 * b.top_thickness_m - 0.5 * b.bottom_thickness_m;
  s.J = 4.0 * a * a * d * d / (a / b.top_thickness_m + a / b.bottom_thickness_m + 2.0 * d / b.web_thickness_m);
  return s;
}

// A mode's cross-section at x: the rigid motion (v0, w0 at the centroid
// height zc, rotation theta) fitted by least squares to the nodes' (v, w),
// the share of the motion it explains, the rotation's share of that, and
// w at the top of each web's outer face.
struct SectionMotion {
  double theta = 0.0, rigid_share = 0.0, twist_share = 0.0, w_left = 0.0, w_right = 0.0;
};
SectionMotion section_motion(const Deck3d& d, const Eigen::Ref<const Vector>& phi, double x_m, double zc,
                             double web_y, double top_z) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  double total = 0.0;
  SectionMotion s;
  for (std::size_t i = 0; i < d.node_m.size(); ++i) {
    const auto& p = d.node_m[i];
    const auto& dofs = d.node_dofs[i];
    if (std::abs(p[0] - x_m) > 1e-9 || dofs[1] < 0 || dofs[2] < 0) continue;
    const double v = phi[dofs[1]], w = phi[dofs[2]];
    const Eigen::Vector3d gv(1.0, 0.0, -(p[2] - zc)), gw(0.0, 1.0, p[1]);
    A += gv * gv.transpose() + gw * gw.transpose();
    rhs += gv * v + gw * w;
    total += v * v + w * w;
    if (std::abs(p[2] - top_z) < 1e-9 && std::abs(p[1] + web_y) < 1e-9) s.w_left = w;
    if (std::abs(p[2] - top_z) < 1e-9 && std::abs(p[1] - web_y) < 1e-9) s.w_right = w;
  }
  const Eigen::Vector3d c = A.ldlt().solve(rhs);
  const double fitted = c.dot(rhs);  // squared norm of the projection
  s.theta = c[2];
  s.rigid_share = fitted / total;
  s.twist_share = c[2] * c[2] * A(2, 2) / fitted;
  return s;
}

struct BoxModes {
  std::optional<double> bending_hz, torsion_hz;
};

BoxModes find_box_modes(const Deck3dOptions& o) {
  {
    const Deck3d d = make_deck_3d(o);
    const BoxGirderSection& b = *o.box;
    ModalOptions mo;
    mo.modes = 8;
    const ModalResult r = modal_analysis(*d.model, mo);
    EXPECT_TRUE(r.status.ok()) << r.status.message();
    BoxModes found;
    for (std::size_t m = 0; m < r.frequencies_hz.size(); ++m) {
      const SectionMotion s = section_motion(d, r.shapes.col(static_cast<Eigen::Index>(m)), 0.5 * kSpan_m,
                                             hand_section(b).zc, 0.5 * b.bottom_width_m, b.depth_m);
      const double sum = std::abs(s.w_left + s.w_right), diff = std::abs(s.w_left - s.w_right);
      // Vertical bending: both webs down together, the section moving rigidly.
      if (!found.bending_hz && diff < 1e-6 * sum && s.rigid_share > 0.99 && sum > 1e-4)
        found.bending_hz = r.frequencies_hz[m];
      // Torsion: the webs' tops move in opposite directions, and rotation
      // is most of the section's motion (the lateral bending mode, also
      // antisymmetric, has twist_share 0.02).
      if (!found.torsion_hz && sum < 1e-6 * diff && s.twist_share > 0.9 && s.rigid_share > 0.8)
        found.torsion_hz = r.frequencies_hz[m];
    }
    return found;
  }
}

const BoxModes& box_modes() {
  static const BoxModes modes = find_box_modes(box_options());
  return modes;
}

TEST(Deck3dBox, SectionPropertiesMatchTheirClosedForms) {
  const Deck3dOptions o = box_options();
  const Section hand = hand_section(*o.box);
  const Deck3d d = make_deck_3d(o);
  EXPECT_NEAR(d.section_area_m2, 4.51, 1e-12);  // 7 x 0.3 + 5 x 0.25 + 2 x 0.4 x 1.45
  EXPECT_NEAR(d.section_area_m2 / hand.A, 1.0, 1e-12);
  EXPECT_NEAR(d.section_I_m4 / hand.I, 1.0, 1e-12);
  EXPECT_NEAR(d.section_polar_m4 / (hand.I + hand.I_lateral), 1.0, 1e-12);
  EXPECT_NEAR(d.section_J_m4 / hand.J, 1.0, 1e-12);
  EXPECT_NEAR(d.section_J_m4, 5.9459, 1e-4);
  // The mesh carries the section's mass plus the two end diaphragms (one
  // element, 0.5 m, filling the void): summed over the lateral DOFs,
  // of which only the bearings' two (about 50 kg each) are missing.
  double lateral_mass = 0.0;
  for (const auto& dofs : d.node_dofs)
    if (dofs[1] >= 0) lateral_mass += d.model->M().coeff(dofs[1], dofs[1]);
  const BoxGirderSection& b = *o.box;
  const double void_area = (b.bottom_width_m - 2.0 * b.web_thickness_m) *
                           (b.depth_m - b.top_thickness_m - b.bottom_thickness_m);
  const double expected = o.density_kg_per_m3 * (hand.A * kSpan_m + 2.0 * 0.5 * void_area);
  EXPECT_NEAR(lateral_mass / expected, 1.0, 5e-4) << lateral_mass << " kg against " << expected;
}

TEST(Deck3dBox, FirstVerticalBendingFrequencyMatchesBeamTheory) {
  const Deck3dOptions o = box_options();
  const Section s = hand_section(*o.box);
  const BoxModes& modes = box_modes();
  ASSERT_TRUE(modes.bending_hz) << "no mode with both webs moving down together";
  const double L = kSpan_m, m = o.density_kg_per_m3 * s.A + 2.0 * o.rail_mass_kg_per_m;
  const double EI = o.E_Pa * s.I;
  // Euler-Bernoulli: f1 = (pi / 2L^2) sqrt(EI / m) = 7.004 Hz. Not a
  // reference for a 2 m deep box on a 25 m span (the FE is 7.26 % below it:
  // shear deformation of the webs, the bearing offset, shear lag): only the
  // order is asserted below, each effect softening the beam.
  const double f_eb = std::numbers::pi / (2.0 * L * L) * std::sqrt(EI / m);
  // Timoshenko with the webs as shear area (kappa A = 2 t_w h_w, the usual
  // box-girder approximation), rotary inertia rho I, and the bearings at
  // the soffit, zc below the axis, as in deck_3d_test: w^2 divides by
  // 1 + 2 (rho A / m) (zc k)^2.
  const double G = o.E_Pa / (2.0 * (1.0 + o.poisson)), k = std::numbers::pi / L;
  const double kGA = G * 2.0 * o.box->web_thickness_m *
                     (o.box->depth_m - o.box->top_thickness_m - o.box->bottom_thickness_m);
  const double J = o.density_kg_per_m3 * s.I;
  const double qa = m * J, qb = -(m * (EI * k * k + kGA) + J * kGA * k * k), qc = kGA * k * k * EI * k * k;
  const double w2 = (-qb - std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa) /
                    (1.0 + 2.0 * (o.density_kg_per_m3 * s.A / m) * std::pow(s.zc * k, 2));
  const double f_timoshenko = std::sqrt(w2) / (2.0 * std::numbers::pi);
  // The reference is the Timoshenko beam (independent of the FE: the
  // section written out above, closed form). Measured -1.05 % (6.496 Hz
  // against 6.565; shear lag: the slabs' far fibres lag the webs, which the
  // beam does not have); tolerance 3 %, 2.9x the measured error, centred on
  // the reference, not on the FE's earlier answer.
  EXPECT_NEAR(*modes.bending_hz / f_timoshenko, 1.0, 0.03) << *modes.bending_hz << " Hz against " << f_timoshenko;
  // Shear lag only softens the Timoshenko beam, shear only Euler-Bernoulli's.
  EXPECT_LT(*modes.bending_hz, f_timoshenko);
  EXPECT_LT(f_timoshenko, f_eb);
  // Against the separately written model at the same node spacing: measured
  // +0.22 % (6.4959 against 6.4818 Hz); tolerance 0.45 %, 2.1x that.
  EXPECT_NEAR(*modes.bending_hz / kReferenceLevel1.bending, 1.0, 0.0045)
      << *modes.bending_hz << " Hz against " << kReferenceLevel1.bending;
}

TEST(Deck3dBox, FirstTorsionFrequencyAgainstStVenantTorsion) {
  const Deck3dOptions o = box_options();
  const Section s = hand_section(*o.box);
  const BoxModes& modes = box_modes();
  ASSERT_TRUE(modes.torsion_hz) << "no mode with the webs moving in opposite directions";
  // St Venant: f_T = (1 / 2L) sqrt(G J / (rho I_p)), I_p the polar moment
  // about the centroid, the rails' rotary inertia added: 25.98 Hz.
  const double G = o.E_Pa / (2.0 * (1.0 + o.poisson));
  double rail_Ip = 0.0;
  for (const double y : o.rail_y_m) rail_Ip += o.rail_mass_kg_per_m * y * y;
  const double f_T = 1.0 / (2.0 * kSpan_m) *
                     std::sqrt(G * s.J / (o.density_kg_per_m3 * (s.I + s.I_lateral) + rail_Ip));
  // Measured -24.4 % (19.65 Hz). Not warping (small for a closed box) but
  // the cross-section: the mode is 86 % rigid rotation, the rest a racking
  // of the cell that only the end diaphragms resist (a box without
  // intermediate diaphragms), and the bearings hold the twist at the soffit
  // only (a solid 5 m x 2 m deck on the same bearings is already 14 % below
  // its St Venant frequency at 25 m, 8 % at 50 m). A finer grid (100 x 24
  // x 10) gives 19.02 Hz.
  // St Venant is not a reference for this box (a 24 % model-form gap): only
  // its order is asserted (distortion and soffit bearings soften).
  EXPECT_LT(*modes.torsion_hz, f_T) << *modes.torsion_hz << " Hz against " << f_T;
  // The reference is the separately written model (distortion, bearings and
  // rails included) at the same node spacing: measured +1.13 % (19.6494
  // against 19.4303 Hz); tolerance 2.3 %, 2.0x that.
  EXPECT_NEAR(*modes.torsion_hz / kReferenceLevel1.torsion, 1.0, 0.023)
      << *modes.torsion_hz << " Hz against " << kReferenceLevel1.torsion;
}

// Intermediate diaphragms hold the cell against racking: the first torsion
// frequency rises towards St Venant's, and vertical bending hardly moves
// (the diaphragms' own mass, the void filled over one element each).
TEST(Deck3dBox, IntermediateDiaphragmsRaiseTheTorsionFrequencyTowardsStVenant) {
  Deck3dOptions o = box_options();
  o.box->intermediate_diaphragms = 3;  // at L/4, L/2, 3L/4
  const BoxModes with = find_box_modes(o);
  const BoxModes& without = box_modes();
  ASSERT_TRUE(with.torsion_hz && without.torsion_hz && with.bending_hz && without.bending_hz);
  const Section s = hand_section(*o.box);
  const double G = o.E_Pa / (2.0 * (1.0 + o.poisson));
  double rail_Ip = 0.0;
  for (const double y : o.rail_y_m) rail_Ip += o.rail_mass_kg_per_m * y * y;
  const double f_T = 1.0 / (2.0 * kSpan_m) *
                     std::sqrt(G * s.J / (o.density_kg_per_m3 * (s.I + s.I_lateral) + rail_Ip));
  std::printf("[box] torsion %.3f Hz with 3 intermediate diaphragms (%.1f %% of St Venant), %.3f Hz without (%.1f %%); "
              "bending %.3f / %.3f Hz\n",
              *with.torsion_hz, 100.0 * (*with.torsion_hz / f_T - 1.0), *without.torsion_hz,
              100.0 * (*without.torsion_hz / f_T - 1.0), *with.bending_hz, *without.bending_hz);
  // Measured -9.5 % of St Venant (23.50 Hz) against -24.4 % without: what
  // is left is mostly the bearings holding the twist at the soffit (a solid
  // deck on the same bearings is 14 % below its St Venant frequency). The
  // diaphragms raise it, and not past St Venant.
  EXPECT_GT(*with.torsion_hz, *without.torsion_hz);
  EXPECT_LT(*with.torsion_hz, f_T) << *with.torsion_hz << " Hz against " << f_T;
  // Against the separately written model with the same diaphragms (one
  // generator element long, at x = 6, 12.5 and 18.5 m) at the same node
  // spacing: torsion measured +2.97 % (23.503 against 22.824 Hz), tolerance
  // 6 %, 2.0x that; bending +0.23 % (6.2230 against 6.2085), tolerance 0.45 %,
  // 2.0x that.
  EXPECT_NEAR(*with.torsion_hz / kReferenceLevel1Diaphragms.torsion, 1.0, 0.06)
      << *with.torsion_hz << " Hz against " << kReferenceLevel1Diaphragms.torsion;
  EXPECT_NEAR(*with.bending_hz / kReferenceLevel1Diaphragms.bending, 1.0, 0.0045)
      << *with.bending_hz << " Hz against " << kReferenceLevel1Diaphragms.bending;
  // Bending: -4.2 % (6.22 Hz against 6.50). Rayleigh with each diaphragm's
  // added mass (the void filled over one element, 7.6 t) as a point mass on
  // the first mode sin(pi x / L) gives -4.9 %; the diaphragms also stiffen.
  const BoxGirderSection& b = *o.box;
  const double void_area = (b.bottom_width_m - 2.0 * b.web_thickness_m) *
                           (b.depth_m - b.top_thickness_m - b.bottom_thickness_m);
  const double diaphragm_kg = o.density_kg_per_m3 * void_area * kSpan_m / 50.0;  // one element of the 50
  const double modal_kg = 0.5 * kSpan_m * (o.density_kg_per_m3 * s.A + 2.0 * o.rail_mass_kg_per_m);
  double added = 0.0;
  for (const double x : {0.25, 0.5, 0.75}) added += diaphragm_kg * std::pow(std::sin(std::numbers::pi * x), 2);
  const double rayleigh = std::sqrt(modal_kg / (modal_kg + added));
  // Measured -4.2 % against the mass-only estimate's -4.9 %: above it (the
  // diaphragms stiffen too) and within 1 % of it.
  const double drop = *with.bending_hz / *without.bending_hz;
  EXPECT_GT(drop, rayleigh) << drop << " against " << rayleigh;
  EXPECT_NEAR(drop, rayleigh, 0.01) << drop << " against " << rayleigh;
}

// Halving the elements at the bearings (nx 50 -> 100; the one-element
// diaphragms halve with them) lowers the torsion frequency in both codes by
// nearly the same factor: the product's mesh dependence is the bearing's (a
// line and points in a 3D solid), not an error of its elements.
TEST(Deck3dBox, TorsionFollowsTheReferenceWhenTheBearingElementsHalve) {
  Deck3dOptions o = box_options();
  o.mesh = Deck3dMesh{{100}, 16, 6};
  const BoxModes fine = find_box_modes(o);
  const BoxModes& coarse = box_modes();
  ASSERT_TRUE(fine.torsion_hz && fine.bending_hz && coarse.torsion_hz);
  std::printf("[box] 100 x 16 x 6: torsion %.4f Hz, bending %.4f Hz\n", *fine.torsion_hz, *fine.bending_hz);
  // Measured +0.85 % (19.197 against 19.035 Hz), tolerance 1.7 %, 2.0x that;
  // bending +0.24 % (6.4655 against 6.4502), tolerance 0.5 %, 2.1x that.
  EXPECT_NEAR(*fine.torsion_hz / kReferenceLevel1Nx100.torsion, 1.0, 0.017)
      << *fine.torsion_hz << " Hz against " << kReferenceLevel1Nx100.torsion;
  EXPECT_NEAR(*fine.bending_hz / kReferenceLevel1Nx100.bending, 1.0, 0.005)
      << *fine.bending_hz << " Hz against " << kReferenceLevel1Nx100.bending;
  // The drop: product 0.9770 (19.197 / 19.649), reference 0.9797 (19.035 /
  // 19.430); measured 0.27 % apart, tolerance 0.55 %, 2.0x that.
  const double product_drop = *fine.torsion_hz / *coarse.torsion_hz;
  const double reference_drop = kReferenceLevel1Nx100.torsion / kReferenceLevel1.torsion;
  EXPECT_NEAR(product_drop / reference_drop, 1.0, 0.0055) << product_drop << " against " << reference_drop;
}

TEST(Deck3dBox, RejectsABoxWithoutAVoidOrAWeb) {
  const auto path_of = [](const Deck3dOptions& o) {
    try {
      make_deck_3d(o);
    } catch (const InputError& e) {
      return e.json_path();
    }
    return std::string("(accepted)");
  };
  Deck3dOptions o = box_options();
  o.box->web_thickness_m = 2.5;  // half the bottom width
  EXPECT_EQ(path_of(o), "/box/web_thickness_m");
  o = box_options();
  o.box->bottom_width_m = 8.0;
  EXPECT_EQ(path_of(o), "/box/bottom_width_m");
  o = box_options();
  o.box->depth_m = 0.5;
  EXPECT_EQ(path_of(o), "/box/depth_m");
  o = box_options();
  o.box->top_thickness_m = -0.1;
  EXPECT_EQ(path_of(o), "/box/top_thickness_m");
  o = box_options();
  o.rail_y_m = {3.6};  // off the 7 m top slab
  EXPECT_EQ(path_of(o), "/rail_y_m/0");
  o = box_options();
  o.mesh->ny = 4;  // three regions on each side need ny >= 6
  EXPECT_EQ(path_of(o), "/mesh/ny");
  o = box_options();
  o.mesh->nx = {3};
  EXPECT_EQ(path_of(o), "/mesh/nx/0");
}

TEST(Deck3dBox, MeshHitsTheRequestedDofsAndKeepsOnlyThePlates) {
  Deck3dOptions o = box_options();
  o.mesh.reset();
  o.target_dofs = 15000;
  const Deck3d d = make_deck_3d(o);
  EXPECT_EQ(d.model->num_dofs(), deck_3d_dofs(o, d.mesh));
  EXPECT_NEAR(d.model->num_dofs(), 15000.0, 0.05 * 15000.0);
  // Away from the end diaphragms, no node in the void carries a DOF.
  const BoxGirderSection& b = *o.box;
  const double void_half = 0.5 * b.bottom_width_m - b.web_thickness_m;
  int void_nodes = 0, void_nodes_with_dofs = 0;
  for (std::size_t i = 0; i < d.node_m.size(); ++i) {
    const auto& p = d.node_m[i];
    if (p[0] < 2.0 || p[0] > kSpan_m - 2.0) continue;
    if (std::abs(p[1]) < void_half - 1e-9 && p[2] > b.bottom_thickness_m + 1e-9 &&
        p[2] < b.depth_m - b.top_thickness_m - 1e-9) {
      ++void_nodes;
      if (d.node_dofs[i][0] >= 0 || d.node_dofs[i][1] >= 0 || d.node_dofs[i][2] >= 0) ++void_nodes_with_dofs;
    }
  }
  EXPECT_GT(void_nodes, 0);
  EXPECT_EQ(void_nodes_with_dofs, 0);
}

}  // namespace
}  // namespace railvsi

// The static correction of the modal structure (residual flexibility at the
// rail DOFs, solver/residual_flexibility.hpp): against the dropped modes of
// a dense generalized eigensolver (Eigen, written apart from the Lanczos
// and CHOLMOD path of the engine), and its limit with every mode kept,
// where it must vanish and leave the run as it was.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <numbers>

#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "solver/modal_operator.hpp"
#include "solver/residual_flexibility.hpp"
#include "test_scenes.hpp"

namespace railvsi {
namespace {

// Every mode of the model: K phi = omega^2 M phi, phi^T M phi = 1.
ModalResult all_modes(const StructureModel& s) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> eig(DenseMatrix(s.K()), DenseMatrix(s.M()));
  EXPECT_EQ(eig.info(), Eigen::Success);
  ModalResult r;
  for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k)
    r.frequencies_hz.push_back(std::sqrt(eig.eigenvalues()[k]) / (2.0 * std::numbers::pi));
  r.shapes = eig.eigenvectors();
  return r;
}

// sum over modes first..last-1 of phi phi^T / omega^2 at the rail DOFs.
DenseMatrix modal_flexibility_at_rails(const StructureModel& s, const ModalResult& m, Eigen::Index first) {
  const auto& rails = s.rail_dofs();
  const auto nr = static_cast<Eigen::Index>(rails.size());
  DenseMatrix F = DenseMatrix::Zero(nr, nr);
  for (Eigen::Index k = first; k < m.shapes.cols(); ++k) {
    const double w = 2.0 * std::numbers::pi * m.frequencies_hz[static_cast<std::size_t>(k)];
    Vector phi(nr);
    for (Eigen::Index i = 0; i < nr; ++i) phi[i] = m.shapes(rails[static_cast<std::size_t>(i)], k);
    F += phi * phi.transpose() / (w * w);
  }
  return F;
}

// 300 km/h over a 10 um dip. (A 1 mm dip lifts the wheels, and the
// instants of loss and re-impact make the histories sensitive to
// round-off: 3e-8 between two runs whose rail flexibilities differ by
// 1e-12.)
Scene with_track() { return testing::small_viaduct_with_dip(300.0, 1e-5); }

TEST(ModalStaticCorrection, ResidualIsTheStaticFlexibilityOfTheDroppedModes) {
  const Scene scene = with_track();
  const StructureModel& s = *scene.structure;
  const ModalResult dense = all_modes(s);
  // The exact static rail flexibility against the dense modes' sum.
  const DenseMatrix F = static_rail_flexibility(s);
  const DenseMatrix F_dense = modal_flexibility_at_rails(s, dense, 0);
  const double scale = F.cwiseAbs().maxCoeff();
  // Measured 1.6e-12 of the largest entry (round-off of both routes).
  fmt::print("static rail flexibility vs dense modes: {:.2e} of the largest entry\n",
             (F - F_dense).cwiseAbs().maxCoeff() / scale);
  EXPECT_LE((F - F_dense).cwiseAbs().maxCoeff(), 1e-11 * scale);
  for (int kept : {10, 40}) {
    StructureOperatorOptions o;
    o.structure_backend = StructureBackend::kModal;
    o.modal_modes = kept;
    const auto basis = make_modal_basis(scene.structure, o);
    ASSERT_EQ(basis->num_modes(), kept);
    const DenseMatrix& R = basis->rail_residual_flexibility();
    const DenseMatrix R_dense = modal_flexibility_at_rails(s, dense, kept);
    // The dropped modes carry most of the rail's flexibility on a track.
    fmt::print("{} modes: largest residual {:.3e} of F's, against the dense dropped modes {:.2e}\n", kept,
               R.cwiseAbs().maxCoeff() / scale, (R - R_dense).cwiseAbs().maxCoeff() / scale);
    EXPECT_GT(R.cwiseAbs().maxCoeff(), 0.1 * scale) << kept;
    // Measured 1.1e-13 (10 modes) and 5.5e-14 (40 modes) of F's largest
    // entry; the residual itself is 0.97 and 0.82 of it.
    EXPECT_LE((R - R_dense).cwiseAbs().maxCoeff(), 1e-12 * scale) << kept;
  }
}

TEST(ModalStaticCorrection, VanishesWithEveryModeKept) {
  const Scene scene = with_track();
  const auto basis = std::make_shared<const ModalBasis>(scene.structure, all_modes(*scene.structure));
  ASSERT_EQ(basis->num_modes(), scene.structure->num_dofs());
  const double scale = static_rail_flexibility(*scene.structure).cwiseAbs().maxCoeff();
  fmt::print("every mode: largest residual {:.2e} of F's\n",
             basis->rail_residual_flexibility().cwiseAbs().maxCoeff() / scale);
  // Measured 1.6e-12 of the static rail flexibility's largest entry (the
  // round-off of F: K^-1 from the factor against the dense modes' sum).
  EXPECT_LE(basis->rail_residual_flexibility().cwiseAbs().maxCoeff(), 1e-11 * scale);
}

// The run with every mode kept: with and without the correction the same
// (the limit), and without the track's dampers (Rayleigh damping, which
// the modes diagonalise exactly) both equal the finite-element run.
// Measured with every mode: R is 1.6e-12 of F's largest entry (9e-12 of
// sqrt(F_ii F_jj)); corrected against uncorrected, forces 7.2e-11 (track)
// and 1.5e-10 (no track) of the peak, deck 8.6e-12 and 1.1e-11; against FE
// (no track) forces 1.4e-10, deck 1.5e-11.
Result run(Scene scene, std::shared_ptr<const ModalBasis> basis, bool correction) {
  if (basis) {
    scene.analysis.structure_backend = StructureBackend::kModal;
    scene.analysis.modal_static_correction = correction;
  }
  const Result r = Simulation(scene, basis ? make_structure_operator(scene, basis) : nullptr).run();
  EXPECT_TRUE(r.status.ok()) << r.status.message();
  if (basis) {
    EXPECT_EQ(r.summary.fidelity.static_correction, correction);
  }
  return r;
}

TEST(ModalStaticCorrection, WithEveryModeKeptTheRunIsTheUncorrectedOne) {
  for (bool track : {true, false}) {
    Scene scene = with_track();
    if (!track) {
      Bridge2dOptions b = testing::small_viaduct_options();
      b.track.reset();
      scene.structure = make_bridge_2d(b);
    }
    const auto basis = std::make_shared<const ModalBasis>(scene.structure, all_modes(*scene.structure));
    const Result corrected = run(scene, basis, true);
    const Result plain = run(scene, basis, false);
    fmt::print("track {}: corrected vs not, forces {:.2e}, deck {:.2e}\n", track,
               testing::relative_history_difference(corrected.histories.contact_force_N, plain.histories.contact_force_N),
               testing::relative_history_difference(corrected.histories.deck_displacement_m,
                                                    plain.histories.deck_displacement_m));
    EXPECT_LE(testing::relative_history_difference(corrected.histories.contact_force_N, plain.histories.contact_force_N),
              1e-9)
        << track;
    EXPECT_LE(testing::relative_history_difference(corrected.histories.deck_displacement_m,
                                                   plain.histories.deck_displacement_m),
              1e-9)
        << track;
    if (!track) {
      const Result fe = run(scene, nullptr, false);
      fmt::print("no track: uncorrected vs FE, forces {:.2e}\n",
                 testing::relative_history_difference(plain.histories.contact_force_N, fe.histories.contact_force_N));
      fmt::print("no track: corrected vs FE, forces {:.2e}, deck {:.2e}\n",
                 testing::relative_history_difference(corrected.histories.contact_force_N, fe.histories.contact_force_N),
                 testing::relative_history_difference(corrected.histories.deck_displacement_m,
                                                      fe.histories.deck_displacement_m));
      EXPECT_LE(testing::relative_history_difference(corrected.histories.contact_force_N, fe.histories.contact_force_N),
                1e-9);
      EXPECT_LE(testing::relative_history_difference(corrected.histories.deck_displacement_m,
                                                     fe.histories.deck_displacement_m),
                1e-9);
    }
  }
}

// "static_correction" in a scene's analysis: read on the modal structure
// (default true), refused with its path on the FE one.
TEST(ModalStaticCorrection, SceneOptionIsReadAndRefusedWithoutModes) {
  const std::string path = RAILVSI_SOURCE_DIR "/jobs/examples/viaduct-ice3.json";
  nlohmann::json doc = read_json_file(path);
  // Without its track: interaction on the modes of a track is refused.
  doc["structure"]["track"] = nullptr;
  doc["analysis"]["structure"] = "modal";
  EXPECT_TRUE(parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs/examples", path).analysis.modal_static_correction);
  doc["analysis"]["static_correction"] = false;
  EXPECT_FALSE(parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs/examples", path).analysis.modal_static_correction);
  doc["analysis"]["structure"] = "fe";
  try {
    parse_scene(doc, RAILVSI_SOURCE_DIR "/jobs/examples", path);
    ADD_FAILURE() << "static_correction on the FE structure was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/analysis/static_correction");
  }
}

}  // namespace
}  // namespace railvsi

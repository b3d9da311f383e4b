// Every matrix reader against files written by another program: SciPy's
// mmwrite and hb_write, and write_beam_files.py from the documented layouts
// (Harwell-Boeing elemental RSE and RUE, Abaqus matrix input, ANSYS mapping). The same
// beam through every reader gives the same K and M to the bit, and the
// natural frequencies of the generator's beam.
#include <cctype>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "solver/modal_analysis.hpp"
#include "beam_files.hpp"
#include "io/matrix_reader.hpp"
#include "io/structure_import.hpp"

namespace railvsi::test {
namespace {

struct BeamFormat {
  const char* K;
  const char* M;
  const char* format;  // what the reader reports
  bool labels;
};

const BeamFormat kFormats[] = {
    {"beam_K_sym.mtx", "beam_M_sym.mtx", "Matrix Market (symmetric)", false},     // scipy mmwrite
    {"beam_K_gen.mtx", "beam_M_gen.mtx", "Matrix Market (general)", false},       // scipy mmwrite
    {"beam_K.rsa", "beam_M.rsa", "Harwell-Boeing RSA, labels from", true},        // scipy hb_write + mapping
    {"beam_K_gen.rua", "beam_M_gen.rua", "Harwell-Boeing RUA", false},            // scipy hb_write
    {"beam_K.rse", "beam_M.rse", "Harwell-Boeing RSE, labels from", true},        // elemental, by the script
    {"beam_K_full.rue", "beam_M_full.rue", "Harwell-Boeing RUE", false},         // elemental, by the script
    {"beam_K.abq", "beam_M.abq", "Abaqus matrix input", true},                    // by the script
};

class BeamReaders : public ::testing::TestWithParam<BeamFormat> {
 protected:
  void SetUp() override { ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)"; }
};

double max_abs_difference(const SparseMatrix& a, const SparseMatrix& b) {
  return (DenseMatrix(a) - DenseMatrix(b)).cwiseAbs().maxCoeff();
}

TEST_P(BeamReaders, ReadTheSameMatricesToTheBit) {
  const BeamFormat& f = GetParam();
  const MatrixFile reference_K = read_matrix_file(beam_files_dir() / "beam_K_sym.mtx", "/K");
  const MatrixFile reference_M = read_matrix_file(beam_files_dir() / "beam_M_sym.mtx", "/M");
  const MatrixFile K = read_matrix_file(beam_files_dir() / f.K, "/K");
  const MatrixFile M = read_matrix_file(beam_files_dir() / f.M, "/M");
  EXPECT_TRUE(K.format.starts_with(f.format)) << K.format;
  ASSERT_EQ(K.A.rows(), 2 * kBeamElements);  // (n + 1) nodes x 2 DOFs, 2 fixed
  ASSERT_EQ(M.A.rows(), K.A.rows());
  // The same doubles: every writer prints 17 significant digits.
  EXPECT_EQ(max_abs_difference(K.A, reference_K.A), 0.0);
  EXPECT_EQ(max_abs_difference(M.A, reference_M.A), 0.0);
  EXPECT_EQ(K.labels.size(), f.labels ? K.A.rows() : 0);
  if (f.labels) {
    // Equation 1 is node 1's rotation (v fixed), equation 2 node 2's vertical.
    EXPECT_EQ(K.labels[0], (DofLabel{1, 6}));
    EXPECT_EQ(K.labels[1], (DofLabel{2, 2}));
    EXPECT_EQ(K.labels.back(), (DofLabel{kBeamElements + 1, 6}));
  }
}

TEST_P(BeamReaders, GiveTheGeneratorsNaturalFrequencies) {
  const BeamFormat& f = GetParam();
  ModalOptions options;
  options.modes = 4;
  const ModalResult generated = modal_analysis(*generated_beam(), options);
  const ModalResult imported = modal_analysis(read_matrix_file(beam_files_dir() / f.K, "/K").A,
                                              read_matrix_file(beam_files_dir() / f.M, "/M").A, options);
  ASSERT_TRUE(generated.status.ok() && imported.status.ok());
  ASSERT_EQ(imported.frequencies_hz.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    // The generator numbers rotation before vertical and forms the element
    // matrices its own way: equal up to rounding (measured 2.7e-15 relative
    // at most, the same for every reader).
    EXPECT_NEAR(imported.frequencies_hz[k] / generated.frequencies_hz[k], 1.0, 2e-14) << "mode " << k + 1;
  }
  // And the closed form n^2 pi / (2 L^2) sqrt(EI/m) of the continuous beam:
  // 10 Hermite elements give the first mode 6.7e-6 high.
  const double f1 = std::numbers::pi / (2 * kBeamSpan_m * kBeamSpan_m) * std::sqrt(kBeamEI_Nm2 / kBeamMass_kg_per_m);
  EXPECT_NEAR(imported.frequencies_hz[0] / f1, 1.0, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, BeamReaders, ::testing::ValuesIn(kFormats),
                         [](const auto& info) {
                           std::string name = info.param.K;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// The map by node numbers and DOF names finds the equations the map by
// equation numbers gives.
TEST(LabelledMaps, MatchTheMapByEquationNumbers) {
  ASSERT_FALSE(beam_files_dir().empty());
  const auto import = [](const char* K, const char* M, const char* map) {
    const nlohmann::json s = {{"import", {{"K", K}, {"M", M}, {"map", map}}}};
    return import_structure(s, nlohmann::json::object(), beam_files_dir());
  };
  const auto by_equation = import("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json");
  const auto abaqus = import("beam_K.abq", "beam_M.abq", "map_abaqus.json");
  const auto ansys = import("beam_K.rsa", "beam_M.rsa", "map_ansys.json");
  for (const auto& model : {abaqus, ansys}) {
    ASSERT_EQ(model->rails().size(), 1u);
    EXPECT_EQ(model->rails()[0].x_m, by_equation->rails()[0].x_m);
    EXPECT_EQ(model->rails()[0].element_dofs, by_equation->rails()[0].element_dofs);
    ASSERT_EQ(model->outputs().size(), 1u);
    EXPECT_EQ(model->outputs()[0].dof, by_equation->outputs()[0].dof);
    EXPECT_EQ(model->outputs()[0].x_m, 10.0);
    // What it matched, for vsi inspect: the rail line by node and DOF name.
    bool rail_note = false;
    for (const auto& note : model->info().import_notes)
      rail_note = rail_note || note.find("rail line 'deck': 11 nodes 1 ... 11 by") != std::string::npos;
    EXPECT_TRUE(rail_note);
  }
}

}  // namespace
}  // namespace railvsi::test

// Every check on import, through the real vsi binary: exit code 2, nothing
// on stdout, and stderr naming the scene, the JSON path, the matrix (or map,
// or coordinates) file and the line. The unit check is a warning (exit 0).
#include <sys/stat.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "beam_files.hpp"
#include "io/harwell_boeing.hpp"
#include "io/matrix_market.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class ImportErrors : public VsiCliTest {
 protected:
  void SetUp() override {
    VsiCliTest::SetUp();
    copy_beam_files(dir_);
  }
  // A scene importing K, M and the map from the test directory.
  std::filesystem::path scene(const std::string& K, const std::string& M, const std::string& map,
                              const std::string& name = "scene.json") const {
    json s = small_scene();
    s["structure"] = {{"import", {{"K", K}, {"M", M}, {"map", map}}},
                      {"damping", {{"ratio", 0.01}, {"f1_hz", 2.0}, {"f2_hz", 30.0}}}};
    s.erase("outputs");
    return write_json(name, s);
  }
  // validate and simulate both refuse with `message` in "file:line: message".
  void expect_refused(const std::filesystem::path& scene_file, const std::string& json_path,
                      const std::string& where, const std::string& message) const {
    for (const char* command : {"validate", "simulate"}) {
      SCOPED_TRACE(command);
      const VsiRun run = vsi(std::string(command) + " '" + scene_file.string() + "'");
      expect_input_error(run, scene_file, json_path);
      EXPECT_NE(run.err.find(where), std::string::npos) << "expected '" << where << "' in: " << run.err;
      EXPECT_NE(run.err.find(message), std::string::npos) << "expected '" << message << "' in: " << run.err;
    }
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(ImportErrors, NonSquareMatrixNamesTheSizeLine) {
  write("K.mtx", "%%MatrixMarket matrix coordinate real general\n% a comment\n20 21 1\n1 1 1.0\n");
  expect_refused(scene("K.mtx", "beam_M_sym.mtx", "map_index.json"), "/structure/import/K", path("K.mtx") + ":3:",
                 "matrix is 20 x 21; a structure matrix must be square");
}

TEST_F(ImportErrors, AFifoGivenAsAMatrixIsRefusedBeforeItIsOpened) {
  // Opening a FIFO for reading blocks until a writer comes: every reader
  // must refuse it from its file type first (vsi() runs under a timeout, so
  // a hang fails the test instead of the suite).
  for (const char* name : {"K.rsa", "K.abq"}) {
    SCOPED_TRACE(name);
    const auto fifo = dir_ / name;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto file = scene(name, "beam_M_sym.mtx", "map_index.json", std::string("scene-") + name + ".json");
    const VsiRun run = vsi("validate '" + file.string() + "'");
    expect_input_error(run, file, "/structure/import/K");
    EXPECT_NE(run.err.find("not a regular file"), std::string::npos) << run.err;
  }
}

TEST_F(ImportErrors, SizesOfKAndMMustAgree) {
  write("M.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n1 1 1.0\n");
  expect_refused(scene("beam_K_sym.mtx", "M.mtx", "map_index.json"), "/structure/import/M", path("M.mtx"),
                 "M is 3 x 3 but K is 20 x 20; sizes must agree");
}

TEST_F(ImportErrors, UnsymmetricEntryNamesBothLines) {
  // Entry (2, 1) on line 4 but (1, 2) on line 5 differs.
  write("K.mtx",
        "%%MatrixMarket matrix coordinate real general\n2 2 4\n1 1 4.0\n2 1 -1.0\n1 2 -1.5\n2 2 4.0\n");
  expect_refused(scene("K.mtx", "beam_M_sym.mtx", "map_index.json"), "/structure/import/K", path("K.mtx") + ":",
                 "the matrix is not symmetric: entry (");
  const VsiRun run = vsi("validate '" + (dir_ / "scene.json").string() + "'");
  EXPECT_NE(run.err.find("(line 5)"), std::string::npos) << run.err;
}

TEST_F(ImportErrors, UnsymmetricHarwellBoeingRua) {
  SparseMatrix A(2, 2);
  A.insert(0, 0) = 4.0;
  A.insert(1, 0) = -1.0;
  A.insert(0, 1) = -1.25;
  A.insert(1, 1) = 4.0;
  write_harwell_boeing(dir_ / "K.rua", A, false);
  // Lines: 4 header, 1 pointer, 1 index, then the values 3 to a line.
  expect_refused(scene("K.rua", "beam_M_sym.mtx", "map_index.json"), "/structure/import/K", path("K.rua") + ":7:",
                 "the matrix is not symmetric: entry (2, 1) is -1 but entry (1, 2) is -1.25 (line 7)");
}

TEST_F(ImportErrors, NonFiniteEntriesNameTheirLine) {
  write("K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 4.0\n2 1 nan\n2 2 4.0\n");
  expect_refused(scene("K.mtx", "beam_M_sym.mtx", "map_index.json"), "/structure/import/K", path("K.mtx") + ":4:",
                 "entry (2, 1) is nan: every entry must be a finite number");
  write("M.abq", "** mass\n1, 6, 1, 6, 1.0\n2, 2, 2, 2, inf\n");
  expect_refused(scene("beam_K.abq", "M.abq", "map_abaqus.json"), "/structure/import/M", path("M.abq") + ":3:",
                 "entry (2, 2) is inf");
}

TEST_F(ImportErrors, ComplexHarwellBoeingIsRefused) {
  std::string text = read_text(dir_ / "beam_K.rsa");
  text.replace(text.find("RSA"), 3, "CSA");
  write("K.rsa", text);
  expect_refused(scene("K.rsa", "beam_M.rsa", "map_index.json"), "/structure/import/K", path("K.rsa") + ":3:",
                 "complex matrices are not read");
}

TEST_F(ImportErrors, RailNodeNotInTheMatrix) {
  json map = json::parse(read_text(dir_ / "map_abaqus.json"));
  map["rail_lines"][0]["nodes"].push_back(99);
  write_json("map.json", map);
  write("nodes.csv", read_text(dir_ / "nodes.csv") + "99,30,0,0\n");
  const auto s = scene("beam_K.abq", "beam_M.abq", "map.json");
  for (const char* command : {"validate", "simulate"}) {
    const VsiRun run = vsi(std::string(command) + " '" + s.string() + "'");
    expect_input_error(run, dir_ / "map.json", "/rail_lines/0/nodes/11");
    EXPECT_NE(run.err.find("rail node 99 is not in the matrices: no equation of " + path("beam_K.abq")),
              std::string::npos)
        << run.err;
  }
}

// Defects (issue 35): the same DOF twice on a rail line was accepted, and
// an equation outside the model was reported at dof_v/<element> whichever
// array and node held it.
TEST_F(ImportErrors, RailLineDofsOutsideTheModelOrRepeatedAreNamedAtTheirEntry) {
  const json map = json::parse(read_text(dir_ / "map_index.json"));
  const auto s = scene("beam_K_sym.mtx", "beam_M_sym.mtx", "map.json");
  auto refused_at = [&](const json& changed, const std::string& json_path, const std::string& message) {
    write_json("map.json", changed);
    for (const char* command : {"validate", "simulate"}) {
      SCOPED_TRACE(command);
      const VsiRun run = vsi(std::string(command) + " '" + s.string() + "'");
      expect_input_error(run, dir_ / "map.json", json_path);
      EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    }
  };
  json outside = map;
  outside["rail_lines"][0]["dof_rot"][4] = 100000;
  refused_at(outside, "/rail_lines/0/dof_rot/4", "equation 100000 outside the model");
  json repeated = map;
  repeated["rail_lines"][0]["dof_v"][3] = repeated["rail_lines"][0]["dof_v"][2];
  refused_at(repeated, "/rail_lines/0/dof_v/3", "also at dof_v/2");
  json rotation_as_vertical = map;
  rotation_as_vertical["rail_lines"][0]["dof_rot"][5] = rotation_as_vertical["rail_lines"][0]["dof_v"][6];
  refused_at(rotation_as_vertical, "/rail_lines/0/dof_v/6", "also at dof_rot/5");
}

TEST_F(ImportErrors, ZUpRailDofsAreRefused) {
  // With z up the rotation about y is -dw/dx, not the +dv/dx of the rail.
  json map = json::parse(read_text(dir_ / "map_abaqus.json"));
  map["rail_lines"][0]["vertical_dof"] = "U3";
  map["rail_lines"][0]["rotation_dof"] = "UR2";
  write_json("map.json", map);
  const auto s = scene("beam_K.abq", "beam_M.abq", "map.json");
  const VsiRun run = vsi("validate '" + s.string() + "'");
  expect_input_error(run, dir_ / "map.json", "/rail_lines/0/rotation_dof");
  EXPECT_NE(run.err.find("U3 with UR2: railvsi needs the vertical displacement along y and the rotation about z "
                         "(U2/UR3)"),
            std::string::npos)
      << run.err;
}

TEST_F(ImportErrors, RailNodesOutOfOrderAlongXNameTheCoordinateLines) {
  std::string csv = read_text(dir_ / "nodes.csv");
  // Node 5 (line 6) at x = 3 m, before node 4 (line 5, x = 6 m).
  csv.replace(csv.find("\n5,8.0,"), 7, "\n5,3.0,");
  write("nodes.csv", csv);
  const auto s = scene("beam_K.rsa", "beam_M.rsa", "map_ansys.json");
  const VsiRun run = vsi("validate '" + s.string() + "'");
  expect_input_error(run, dir_ / "map_ansys.json", "/rail_lines/0/nodes/4");
  EXPECT_NE(run.err.find("rail nodes must be ordered along x: node 5 (x = 3 m, " + path("nodes.csv") +
                         " line 6) follows node 4 (x = 6 m, line 5)"),
            std::string::npos)
      << run.err;
}

TEST_F(ImportErrors, ConstrainedDofLeftInIsAZeroRow) {
  // The beam with its first support's vertical DOF left in: a row and
  // column of zeros in K (M gives it mass, as a lumped mass would).
  SparseMatrix K = read_matrix_market(dir_ / "beam_K_sym.mtx", "/");
  SparseMatrix M = read_matrix_market(dir_ / "beam_M_sym.mtx", "/");
  const auto grow = [](const SparseMatrix& A, double corner) {
    std::vector<Triplet> t{{0, 0, corner}};
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
        t.emplace_back(static_cast<int>(it.row()) + 1, static_cast<int>(it.col()) + 1, it.value());
    SparseMatrix B(A.rows() + 1, A.cols() + 1);
    B.setFromTriplets(t.begin(), t.end());
    return B;
  };
  write_matrix_market(dir_ / "K.mtx", grow(K, 0.0));
  write_matrix_market(dir_ / "M.mtx", grow(M, 1000.0));
  json map = json::parse(read_text(dir_ / "map_index.json"));
  write_json("map.json", map);
  expect_refused(scene("K.mtx", "M.mtx", "map.json"), "/structure/import/K", path("K.mtx"),
                 "equation 1 has an all-zero row and column in K: a constrained DOF left in the matrix");
}

TEST_F(ImportErrors, MassNotPositiveDefiniteOnTheRailDofs) {
  // No mass at the midspan node (equation 10, node 6 UY; the output point's).
  SparseMatrix M = read_matrix_market(dir_ / "beam_M_sym.mtx", "/");
  M.prune([](Eigen::Index row, Eigen::Index col, double) { return row != 9 && col != 9; });
  write_matrix_market(dir_ / "M.mtx", M);
  expect_refused(scene("beam_K.abq", "M.mtx", "map_abaqus.json"), "/structure/import/M", path("M.mtx"),
                 "M is not positive definite on the rail DOFs: pivot 0.000e+00 at equation 10 (node 6, U2), rail "
                 "line 'deck' node 6 U2");
}

TEST_F(ImportErrors, BadMappingLabelNamesItsLine) {
  std::string mapping = read_text(dir_ / "beam_K.mapping");
  mapping.replace(mapping.find("UY"), 2, "UQ");
  write("beam_K.mapping", mapping);
  expect_refused(scene("beam_K.rsa", "beam_M.rsa", "map_ansys.json"), "/structure/import/K",
                 path("beam_K.mapping") + ":3:", "DOF label 'UQ' is not one of UX, UY, UZ, ROTX, ROTY, ROTZ");
}

TEST_F(ImportErrors, UnitMistakesAreWarningsNamingTheUnit) {
  // The beam's f1 is 3.10 Hz: K in kN/m puts it at 0.098 Hz; a beam four
  // times as stiff (6.21 Hz) with M in t at 196 Hz.
  const SparseMatrix K = read_matrix_market(dir_ / "beam_K_sym.mtx", "/");
  const SparseMatrix M = read_matrix_market(dir_ / "beam_M_sym.mtx", "/");
  write_matrix_market(dir_ / "K_kN.mtx", SparseMatrix(K * 1e-3));
  write_matrix_market(dir_ / "K4.mtx", SparseMatrix(K * 4.0));
  write_matrix_market(dir_ / "M_t.mtx", SparseMatrix(M * 1e-3));
  const std::pair<std::filesystem::path, std::string> cases[] = {
      {scene("K_kN.mtx", "beam_M_sym.mtx", "map_index.json", "kN.json"),
       "Hz is below 0.5 Hz: is K in kN/m instead of N/m, or M in g? With K in N/m it would be 3.105 Hz"},
      {scene("K4.mtx", "M_t.mtx", "map_index.json", "t.json"),
       "Hz is above 100 Hz: is M in t (tonnes) instead of kg, or K in N/mm with M in kg? With M in kg it would be "
       "6.209 Hz"}};
  for (const auto& [s, message] : cases) {
    const VsiRun run = vsi("validate '" + s.string() + "'");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("warning: " + s.string() + ": /structure/import: first natural frequency "),
              std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    const VsiRun inspect = vsi("inspect '" + s.string() + "' --modes 1 --format json");
    EXPECT_EQ(inspect.exit_code, 0) << inspect.err;
    EXPECT_NE(json::parse(inspect.out)["modal_analysis"]["units_warning"].get<std::string>().find(message),
              std::string::npos);
  }
  // The beam in N/m and kg: no warning.
  const VsiRun kg = vsi("validate '" + scene("beam_K_sym.mtx", "beam_M_sym.mtx", "map_index.json").string() + "'");
  EXPECT_EQ(kg.exit_code, 0) << kg.err;
  EXPECT_EQ(kg.err, "");
}

}  // namespace
}  // namespace railvsi::test

// A bound of the structure in a scene (structure.variant, EN 1991-2
// 6.4.6.3): an imported model scales its whole M and K, a generated deck its
// mass per metre and EI. The first frequency then scales as
// sqrt(EI factor / mass factor): 1.2 / 1.1 for the factors 1.44 and 1.21.
#include <cmath>

#include "exported_beam.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class StructureVariant : public VsiCliTest {
 protected:
  double first_frequency_hz(const json& scene) const {
    const VsiRun run = vsi("inspect --format json '" + write_json("scene.json", scene).string() + "'");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return json::parse(run.out)["modal_analysis"]["modes"][0]["frequency_hz"].get<double>();
  }
};

TEST_F(StructureVariant, ScalesTheImportedMatricesAndTheGeneratedDeck) {
  const ExportedBeam beam = exported_beam(8, 10.0, true);
  write("K.mtx", matrix_market(beam.K, true));
  write("M.mtx", matrix_market(beam.M, false));
  write_json("map.json", beam.map);
  const json variant = {{"mass_factor", 1.21}, {"EI_factor", 1.44}};
  for (json scene : {imported_scene(small_scene()), small_scene()}) {
    const double nominal_hz = first_frequency_hz(scene);
    scene["structure"]["variant"] = variant;
    // The ratio is exact for a scaled eigenproblem; 1e-9 covers the eigensolver's round-off.
    EXPECT_NEAR(first_frequency_hz(scene) / nominal_hz, 1.2 / 1.1, 1e-9) << scene["structure"].dump();
  }
}

}  // namespace
}  // namespace railvsi::test

// The cost model's prediction for the modal moving-force rung against its
// measured CPU time, as `vsi price` measures a modal row (thread CPU of the
// modal basis, then of the run on it), on two scenes:
//   hslm-beam   jobs/examples/hslm-a1-beam.json: HSLM-A1 at 360 km/h on the
//               25 m beam (102 DOFs, 50 axles, 2 output points);
//   viaduct     jobs/examples/viaduct-ice3-german.json's structure (2,296
//               DOFs, track) with HSLM-A1 at 300 km/h as moving forces
//               (50 axles, 3 output points), no irregularity.
// Each at the dt ladder of `vsi price` around the policy's 0.5 ms, with the
// modes up to 1.2 x the code cut-off (vsi price's: 61.5 and 53.0 Hz). Each
// measurement is the least of `reps` repetitions (others share the machine).
// Prints measured / predicted for the basis (setup), the run (loop) and
// both, and exits 1 when a total ratio lies outside the band the model
// claims (kBandLow..kBandHigh below; docs/accuracy-and-price.md).
//
// Run by hand: OPENBLAS_NUM_THREADS=1 build/tests/bench/cost_model_bench [reps]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/modal_moving_forces.hpp"
#include "cpu_time.hpp"
#include "io/scene_loader.hpp"
#include "planning/cost_model.hpp"
#include "solver/modal_basis.hpp"

namespace {

using namespace railvsi;
using nlohmann::json;
namespace fs = std::filesystem;

// The band of measured / predicted CPU the model is held to (whole modal
// row: basis and run), on this machine class.
constexpr double kBandLow = 0.5, kBandHigh = 2.0;

struct Case {
  std::string name;
  fs::path file;
  double cutoff_hz;
  void (*edit)(json&);
};

template <class F>
double least_cpu_s(int reps, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    const double t0 = bench::thread_cpu_s();
    f();
    best = std::min(best, bench::thread_cpu_s() - t0);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const fs::path examples = fs::path(RAILVSI_EXAMPLES_DIR);
  const std::vector<Case> cases{
      {"hslm-beam", examples / "hslm-a1-beam.json", 1.2 * 51.2287, [](json&) {}},
      {"viaduct", examples / "viaduct-ice3-german.json", 1.2 * 44.2, [](json& d) {
         d["train"] = "HSLM-A1";
         d.erase("irregularity");
         d["analysis"] = {{"hht_alpha", -0.05}, {"dt_s", 5e-4}};
       }}};
  bool within = true;
  std::printf("%-10s %6s %6s %7s %5s %7s %10s %10s %10s %10s %10s %10s %8s\n", "scene", "dofs", "modes", "loads",
              "dt_ms", "steps", "basis_s", "pred_s", "run_s", "pred_s", "total_s", "pred_s", "ratio");
  for (const Case& c : cases) {
    json doc = json::parse(std::ifstream(c.file));
    c.edit(doc);
    const Scene base = parse_scene(doc, c.file.parent_path(), c.file.string());
    ModalBasisOptions o;
    o.max_frequency_hz = c.cutoff_hz;
    std::shared_ptr<const ModalBasis> basis;
    const double basis_s = least_cpu_s(reps, [&] { basis = std::make_shared<const ModalBasis>(base.structure, o); });
    for (const double dt_s : {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4}) {
      Scene s = base;
      s.analysis.dt_s = dt_s;
      const double run_s = least_cpu_s(reps, [&] { (void)run_modal_moving_forces(s, *basis); });
      const CostInputs in = cost_inputs(s, StructureBackend::kModal, basis->num_modes());
      const CostPrediction p = predict_cost(in);
      const double ratio = (basis_s + run_s) / p.total_cpu_s();
      within = within && ratio >= kBandLow && ratio <= kBandHigh;
      std::printf("%-10s %6.0f %6d %7.0f %5.3g %7.0f %10.3g %10.3g %10.3g %10.3g %10.3g %10.3g %8.3g\n",
                  c.name.c_str(), in.structure_dofs, basis->num_modes(), in.axles + in.output_points, 1e3 * dt_s,
                  in.steps, basis_s, p.setup_cpu_s, run_s, p.loop_cpu_s, basis_s + run_s, p.total_cpu_s(), ratio);
    }
  }
  std::printf("measured / predicted CPU %s the band [%.2g, %.2g]\n", within ? "within" : "OUTSIDE", kBandLow,
              kBandHigh);
  return within ? 0 : 1;
}

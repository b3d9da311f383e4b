// The hybrid structure (track in FE, bridge in its modes) against the full
// finite-element structure, at the same dt and contact law: the envelope
// quantities a study stores and the CPU each takes, for generated 3D decks
// (three 25 m spans of hexahedra, two rails on pads) under ICE3 at
// 300 km/h on the German low-interference profile, and over a 20 mm dip.
// CPU is the thread's own time: setup (modes, constraint modes, reduction,
// factor, rail flexibility, statics) and the time loop, separately.
//
// Run by hand:
//   OPENBLAS_NUM_THREADS=1 build/tests/bench/hybrid_bench [DOFS ...] [--cutoffs 30,60,3x] [--dip] [--partition]
// default DOFS 6000 20000; "3x" in --cutoffs is the planner's cut-off
// (kHybridCutoffFactor x the code frequency). Other scenes (--help): a dip
// of another depth, place or length (--dip-depth-mm, --dip-x-m,
// --dip-length-m), --speed-kmh, --train and --vehicles N (its first N
// vehicles), --spans 25,25 and --approach-m (the generated deck),
// --no-profile (the dip alone), or --scene FILE (a scene document's
// structure, train and analysis, the dip added where asked); --fe-cache DIR keeps each FE reference run's
// values in DIR and reads them from there the next time (the FE run of the
// 20,000-DOF deck takes minutes); --cost runs the hybrid structure only and
// prints its parts against the cost model's prediction (--train NAME: a
// library train instead of ICE3); --duration-s T simulates T seconds only
// (the seed-scale deck: 0.5 s is the paper's 2,000 steps); --fixed-interface: the
// interior's modes with the interface held (Craig-Bampton) instead of the bridge's
// free-interface modes (BridgeModes); --partition prints how the hybrid structure
// would split each deck (track, interface, interior DOFs) and runs nothing;
// --frequencies-out PREFIX (with --cost) writes the interior modes'
// frequencies to PREFIX-DOFS-CUTOFF.txt, one a line, to the last bit, and
// beside it the bridge's own frequencies (-bridge.txt), the reduced K, M, C
// (-K.bin ...: int row, int column, double value) and the run's values
// (-values.txt): two builds compared (tests/bench/compare_hybrid_outputs.py).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <utility>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cpu_time.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/job_envelopes.hpp"
#include "generators/deck_3d.hpp"
#include "io/irregularity_loader.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "solver/hybrid_operator.hpp"
#include "solver/structure_backend.hpp"
#include "planning/cost_model.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/effects_planner.hpp"

namespace railvsi {
namespace {

struct Values {
  double displacement_m = NAN, filtered_acc_mps2 = NAN, min_force_N = NAN, unloading = NAN, carbody_mps2 = NAN,
         contact_loss_s = NAN;
  // Not among the targets, but where a landing's impact shows first: the
  // unfiltered deck acceleration, the largest wheel force (the landing's
  // peak) and the longest loss of one wheel.
  double raw_acc_mps2 = NAN, max_force_N = NAN, wheel_loss_s = NAN;
  double setup_cpu_s = 0.0, loop_cpu_s = 0.0;
  std::string backend;
};

std::optional<double> max_over_points(const JobEnvelopes& e, bool acceleration) {
  std::optional<double> m;
  for (const auto& p : e.points) {
    const auto& v = acceleration ? p.max_abs_acceleration_mps2 : p.max_abs_displacement_m;
    if (!v) return std::nullopt;
    m = std::max(m.value_or(0.0), *v);
  }
  return m;
}

Values run(const Scene& scene, double code_cutoff_hz) {
  Values v;
  const double t0 = bench::thread_cpu_s();
  const std::shared_ptr<const StructureOperator> op = make_structure_operator(scene);
  if (const auto* hybrid = dynamic_cast<const HybridOperator*>(op.get())) {
    const HybridBasisSummary& h = hybrid->basis().summary();
    std::printf("  hybrid setup CPU: constraint modes %.2f s, interior modes %.2f s (%d more factors: %.2f s), "
                "reduction %.2f s; interior modes' largest relative residual %.2e%s\n",
                h.constraint_modes_cpu_s, h.interior_modes_cpu_s, h.factorizations, h.interior_factor_cpu_s,
                h.reduction_cpu_s, h.interior_max_residual,
                h.interior_single_vector_fallback ? fmt::format(" (block Lanczos's {:.2e} failed the check: computed again "
                                                                "one vector at a time)",
                                                                h.interior_block_residual)
                                                        .c_str()
                                                  : "");
  }
  const Simulation sim(scene, op);
  const double t1 = bench::thread_cpu_s();
  const Result r = sim.run();
  const double t2 = bench::thread_cpu_s();
  v.setup_cpu_s = t1 - t0;
  v.loop_cpu_s = t2 - t1;
  v.backend = r.summary.fidelity.structure_backend;
  if (!r.status.ok()) {
    std::printf("  run failed: %s\n", r.status.message().c_str());
    return v;
  }
  const JobEnvelopes e = compute_envelopes(r, scene.analysis.dt_s, scene.analysis.history_stride, code_cutoff_hz);
  v.displacement_m = max_over_points(e, false).value_or(NAN);
  v.filtered_acc_mps2 = max_over_points(e, true).value_or(NAN);
  v.min_force_N = e.min_contact_force_N.value_or(NAN);
  v.unloading = e.max_unloading_ratio.value_or(NAN);
  v.carbody_mps2 = e.max_abs_carbody_acceleration_mps2.value_or(NAN);
  v.contact_loss_s = r.summary.contact_loss_s;
  v.raw_acc_mps2 = e.max_abs_acceleration_unfiltered_mps2.value_or(NAN);
  v.wheel_loss_s = e.max_contact_loss_s.value_or(NAN);
  v.max_force_N = 0.0;
  for (const auto& wheel : r.histories.contact_force_N)
    for (double q : wheel) v.max_force_N = std::max(v.max_force_N, q);
  return v;
}

double rel(double a, double b) { return (a - b) / std::abs(b); }

// One comparison's scene: a generated 3D deck (three 25 m spans unless
// `spans_m`) or a scene document (`scene_file`), and what runs over it.
struct Case {
  std::string scene_file;             // a scene document instead of a generated deck
  std::vector<double> spans_m;        // empty: the generator's three 25 m spans
  std::string train = "ICE3";
  int vehicles = 0;                   // > 0: the train's first N vehicles only
  double speed_kmh = 300.0;
  bool profile = true;                // German low, seed 1
  bool dip = false;
  double dip_depth_m = 0.02, dip_x_m = 37.0, dip_length_m = 1.0;
  double approach_m = 0.0;            // 0: the whole train on the track before the bridge
  double duration_s = 0.0;

  // What the FE reference run is kept under in the cache (every field that
  // changes it; the defaults keep the names of the runs cached before).
  std::string key(int dofs) const {
    std::string k = scene_file.empty() ? fmt::format("fe-{}", dofs)
                                       : "fe-" + std::filesystem::path(scene_file).stem().string();
    if (!spans_m.empty()) k += fmt::format("-spans{}", fmt::join(spans_m, "x"));
    if (train != "ICE3") k += "-" + train;
    if (vehicles > 0) k += fmt::format("-{}veh", vehicles);
    if (speed_kmh != 300.0) k += fmt::format("-{}kmh", speed_kmh);
    if (!profile) k += "-smooth";
    if (dip) {
      k += "-dip";
      if (dip_depth_m != 0.02 || dip_x_m != 37.0 || dip_length_m != 1.0)
        k += fmt::format("{}mm-at{}m-{}m", 1e3 * dip_depth_m, dip_x_m, dip_length_m);
    }
    if (approach_m > 0.0) k += fmt::format("-approach{}", approach_m);
    if (duration_s > 0.0) k += fmt::format("-{}s", duration_s);
    return k;
  }
  std::string describe() const {
    std::string d = fmt::format("{}{} {} km/h", train, vehicles > 0 ? fmt::format(" ({} vehicles)", vehicles) : "",
                                speed_kmh);
    d += profile ? ", German low seed 1" : ", no profile";
    if (dip) d += fmt::format(" + {} mm x {} m dip at {} m", 1e3 * dip_depth_m, dip_length_m, dip_x_m);
    if (duration_s > 0.0) d += fmt::format(", {} s", duration_s);
    return d;
  }
};

nlohmann::json irregularity_json(const Case& c) {
  nlohmann::json irr = nlohmann::json::object();
  if (c.profile) irr = {{"spectrum", "german-low"}, {"seed", 1}};
  if (c.dip) irr["defects"] = {{{"type", "dip"}, {"x_m", c.dip_x_m}, {"length_m", c.dip_length_m}, {"depth_m", c.dip_depth_m}}};
  return irr;
}

Scene deck_scene(int dofs, const Case& c) {
  if (!c.scene_file.empty()) {
    // The document's structure, train, speed and analysis; the case's
    // irregularity only where it asks a dip.
    Scene s = load_scene(c.scene_file);
    if (c.dip) {
      const RailLine& rail = s.structure->rails().front();
      s.irregularity = parse_irregularity(irregularity_json(c), ".", TrackRange{rail.start_m(), rail.end_m()});
    }
    s.analysis.history_stride = 1;
    if (c.duration_s > 0.0) s.analysis.duration_s = c.duration_s;
    return s;
  }
  Deck3dOptions d;
  d.target_dofs = dofs;
  if (!c.spans_m.empty()) d.spans_m = c.spans_m;
  Scene s;
  s.train = load_library_train(c.train);
  if (c.vehicles > 0 && static_cast<size_t>(c.vehicles) < s.train.vehicles.size()) s.train.vehicles.resize(c.vehicles);
  d.approach_m = c.approach_m > 0.0 ? c.approach_m : s.train.length_m() + 10.0;  // the whole train starts on the track
  s.structure = make_deck_3d(d).model;
  s.speed_mps = c.speed_kmh / 3.6;
  const nlohmann::json irr = irregularity_json(c);
  const RailLine& rail = s.structure->rails().front();
  if (!irr.empty()) s.irregularity = parse_irregularity(irr, ".", TrackRange{rail.start_m(), rail.end_m()});
  s.analysis.dt_s = 2.5e-4;
  s.analysis.contact.law = "hertz";
  s.analysis.contact.rail_lines = {0, 1};
  s.analysis.history_stride = 1;
  if (c.duration_s > 0.0) s.analysis.duration_s = c.duration_s;
  return s;
}

void partition(int dofs) {
  const double t0 = bench::thread_cpu_s();
  const Scene s = deck_scene(dofs, Case{});
  const double t1 = bench::thread_cpu_s();
  const HybridPartition p = hybrid_partition(*s.structure);
  std::printf("3D deck, %d DOFs (generated in %.1f s CPU): track %d, interface %d, interior %d DOFs (%.2f s CPU)\n",
              s.structure->num_dofs(), t1 - t0, p.track_dofs, p.interface_dofs, p.interior_dofs,
              bench::thread_cpu_s() - t1);
}

// The FE run's values from `cache_dir` when they were kept there, else run
// and kept.
Values fe_values(const Scene& s, double code_hz, const std::string& cache_dir, const std::string& name) {
  const std::string file = cache_dir.empty() ? std::string() : cache_dir + "/" + name + ".json";
  if (!file.empty()) {
    std::ifstream in(file);
    if (in) {
      const nlohmann::json j = nlohmann::json::parse(in);
      Values v;
      v.displacement_m = j.at("displacement_m");
      v.filtered_acc_mps2 = j.at("filtered_acc_mps2");
      v.min_force_N = j.at("min_force_N");
      v.unloading = j.at("unloading");
      v.carbody_mps2 = j.at("carbody_mps2");
      v.contact_loss_s = j.at("contact_loss_s");
      v.raw_acc_mps2 = j.value("raw_acc_mps2", NAN);
      v.max_force_N = j.value("max_force_N", NAN);
      v.wheel_loss_s = j.value("wheel_loss_s", NAN);
      v.setup_cpu_s = j.at("setup_cpu_s");
      v.loop_cpu_s = j.at("loop_cpu_s");
      std::printf("(FE values read from %s)\n", file.c_str());
      return v;
    }
  }
  const Values v = run(s, code_hz);
  if (!file.empty())
    std::ofstream(file) << nlohmann::json{{"displacement_m", v.displacement_m},
                                          {"filtered_acc_mps2", v.filtered_acc_mps2},
                                          {"min_force_N", v.min_force_N},
                                          {"unloading", v.unloading},
                                          {"carbody_mps2", v.carbody_mps2},
                                          {"contact_loss_s", v.contact_loss_s},
                                          {"raw_acc_mps2", v.raw_acc_mps2},
                                          {"max_force_N", v.max_force_N},
                                          {"wheel_loss_s", v.wheel_loss_s},
                                          {"setup_cpu_s", v.setup_cpu_s},
                                          {"loop_cpu_s", v.loop_cpu_s}}
                               .dump();
  return v;
}

// A cut-off of 0 is the planner's: kHybridCutoffFactor x the code frequency.
void compare(int dofs, const Case& c, const std::vector<double>& cutoffs, const std::string& cache_dir,
             BridgeModes bridge_modes) {
  Scene s = deck_scene(dofs, c);
  s.analysis.hybrid_bridge_modes = bridge_modes;
  const auto f = deck_frequencies(*s.structure);
  const double code_hz = code_cutoff_hz(f.f0_hz, f.f3_hz);
  std::printf("\n## %s, %d DOFs, %s; f0 %.3f Hz, f3 %.3f Hz, filter %.3g Hz\n",
              c.scene_file.empty() ? "3D deck" : c.scene_file.c_str(), s.structure->num_dofs(), c.describe().c_str(),
              f.f0_hz, f.f3_hz, code_hz);
  s.analysis.structure_backend = StructureBackend::kFiniteElements;
  const Values fe = fe_values(s, code_hz, cache_dir, c.key(dofs));
  std::printf("FE: disp %.6e m, acc %.6f m/s2 (unfiltered %.4f), Qmin %.1f N, Qmax %.1f N, dQ/Q %.5f, car body %.5f "
              "m/s2, loss %.6f s (longest wheel %.6f s); CPU setup %.2f s, loop %.2f s\n",
              fe.displacement_m, fe.filtered_acc_mps2, fe.raw_acc_mps2, fe.min_force_N, fe.max_force_N, fe.unloading,
              fe.carbody_mps2, fe.contact_loss_s, fe.wheel_loss_s, fe.setup_cpu_s, fe.loop_cpu_s);
  std::printf("| cut-off | backend | disp. | acc. (filtered) | Q min | dQ/Q | car body | loss (ms) | longest wheel loss (ms) "
              "| acc. unfiltered | Q max | CPU setup / loop (FE / hybrid) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (double cutoff : cutoffs) {
    if (cutoff <= 0.0) cutoff = kHybridCutoffFactor * code_hz;
    s.analysis.structure_backend = StructureBackend::kHybrid;
    s.analysis.modal_cutoff_hz = cutoff;
    const Values h = run(s, code_hz);
    std::printf("| %.1f Hz | %s | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | %.3f / %.3f | %.3f / %.3f | "
                "%+.3f %% | %+.3f %% | %.2f / %.2f s (%.1fx / %.1fx) |\n",
                cutoff, h.backend.c_str(), 100 * rel(h.displacement_m, fe.displacement_m),
                100 * rel(h.filtered_acc_mps2, fe.filtered_acc_mps2), 100 * rel(h.min_force_N, fe.min_force_N),
                100 * rel(h.unloading, fe.unloading), 100 * rel(h.carbody_mps2, fe.carbody_mps2),
                1e3 * h.contact_loss_s, 1e3 * fe.contact_loss_s, 1e3 * h.wheel_loss_s, 1e3 * fe.wheel_loss_s,
                100 * rel(h.raw_acc_mps2, fe.raw_acc_mps2), 100 * rel(h.max_force_N, fe.max_force_N), h.setup_cpu_s,
                h.loop_cpu_s,
                fe.setup_cpu_s / h.setup_cpu_s, fe.loop_cpu_s / h.loop_cpu_s);
    std::fflush(stdout);
  }
}

// The cost model's hybrid terms against the measured parts, without the FE
// run: the reduction once per structure (HybridBasisSummary's parts), the
// rest of the setup (the reduced operator's factor, rail flexibility,
// statics) and the loop.
void cost(int dofs, const std::vector<double>& cutoffs, double duration_s, const std::string& train,
          BridgeModes bridge_modes, const std::string& frequencies_out) {
  Case c;
  c.train = train;
  c.duration_s = duration_s;
  Scene s = deck_scene(dofs, c);
  s.analysis.hybrid_bridge_modes = bridge_modes;
  const HybridPartition part = hybrid_partition(*s.structure);
  std::printf("\n## cost: %s (%d axles) over a 3D deck, %d DOFs (track %d, interface %d, interior %d; %zu rail DOFs), "
              "%ld steps\n",
              train.c_str(), s.train.num_axles(), s.structure->num_dofs(), part.track_dofs, part.interface_dofs, part.interior_dofs,
              s.structure->rail_dofs().size(), planned_steps(s));
  std::printf("| cut-off | modes | constraint modes | interior modes | reduction | structure setup (pred.) | per-dt setup "
              "(pred.) | loop (pred.) | total / predicted |\n|---|---|---|---|---|---|---|---|---|\n");
  for (double cutoff : cutoffs) {
    s.analysis.structure_backend = StructureBackend::kHybrid;
    s.analysis.modal_cutoff_hz = cutoff;
    const double t0 = bench::thread_cpu_s();
    const std::shared_ptr<const StructureOperator> op = make_structure_operator(s);
    const Simulation sim(s, op);
    const double t1 = bench::thread_cpu_s();
    const Result r = sim.run();
    const double t2 = bench::thread_cpu_s();
    const auto* hybrid = dynamic_cast<const HybridOperator*>(op.get());
    if (!hybrid || !r.status.ok()) {
      std::printf("| %.0f Hz | the hybrid run failed: %s |\n", cutoff, r.status.message().c_str());
      continue;
    }
    const HybridBasisSummary& h = hybrid->basis().summary();
    const double structure_s = h.constraint_modes_cpu_s + h.interior_modes_cpu_s + h.reduction_cpu_s;
    const CostPrediction p = predict_cost(cost_inputs(s, StructureBackend::kHybrid, hybrid->basis().num_modes()));
    std::printf("| %.0f Hz | %d | %.2f s | %.2f s | %.2f s | %.2f (%.2f) s | %.2f (%.2f) s | %.2f (%.2f) s | %.2f |\n",
                cutoff, hybrid->basis().num_modes(), h.constraint_modes_cpu_s, h.interior_modes_cpu_s,
                h.reduction_cpu_s, structure_s, p.structure_setup_cpu_s, t1 - t0 - structure_s,
                p.setup_cpu_s - p.structure_setup_cpu_s, t2 - t1, p.loop_cpu_s, (t2 - t0) / p.total_cpu_s());
    std::printf("  (interior modes: %d more factors%s, %.2f s of factoring; largest residual %.2e%s)\n",
                h.factorizations, h.shared_bridge_factor ? " (first shift: the constraint modes' factor)" : "",
                h.interior_factor_cpu_s, h.interior_max_residual,
                h.interior_single_vector_fallback ? ", block Lanczos failed its check: computed again one vector at a time"
                                                  : "");
    if (!frequencies_out.empty()) {
      // Every interior mode's frequency to the last bit: two builds compared mode by mode.
      const std::string prefix = fmt::format("{}-{}-{:.0f}", frequencies_out, dofs, cutoff);
      std::ofstream out(prefix + ".txt");
      for (double f : hybrid->basis().frequencies_hz()) out << fmt::format("{:.17g}\n", f);
      // The bridge's own (free-interface) frequencies, the reduced K, M, C
      // (binary triplets: int row, int column, double value) and the run's
      // deck and wheel values (deck acceleration filtered at a fixed 30 Hz),
      // for the same comparison.
      std::ofstream bridge(prefix + "-bridge.txt");
      for (double f : hybrid->basis().bridge_frequencies_hz()) bridge << fmt::format("{:.17g}\n", f);
      const StructureModel& red = hybrid->basis().reduced();
      for (const auto& [name, A] : {std::pair{"K", &red.K()}, std::pair{"M", &red.M()}, std::pair{"C", &red.C()}}) {
        std::ofstream bin(prefix + "-" + name + ".bin", std::ios::binary);
        for (int j = 0; j < A->outerSize(); ++j)
          for (SparseMatrix::InnerIterator it(*A, j); it; ++it) {
            const int rc[2] = {static_cast<int>(it.row()), j};
            const double v = it.value();
            bin.write(reinterpret_cast<const char*>(rc), sizeof rc);
            bin.write(reinterpret_cast<const char*>(&v), sizeof v);
          }
      }
      const JobEnvelopes e = compute_envelopes(r, s.analysis.dt_s, s.analysis.history_stride, 30.0);
      std::ofstream values(prefix + "-values.txt");
      values << fmt::format("displacement_m {:.17g}\nfiltered_acc_30hz_mps2 {:.17g}\nmin_force_N {:.17g}\n"
                            "unloading {:.17g}\ncarbody_mps2 {:.17g}\ncontact_loss_s {:.17g}\n",
                            max_over_points(e, false).value_or(NAN), max_over_points(e, true).value_or(NAN),
                            e.min_contact_force_N.value_or(NAN), e.max_unloading_ratio.value_or(NAN),
                            e.max_abs_carbody_acceleration_mps2.value_or(NAN), r.summary.contact_loss_s);
    }
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace railvsi

int main(int argc, char** argv) {
  std::vector<int> dofs;
  std::vector<double> cutoffs{30.0, 60.0, 100.0};
  bool partition_only = false, cost_only = false;
  railvsi::Case c;
  std::string cache_dir, frequencies_out;
  railvsi::BridgeModes bridge_modes = railvsi::BridgeModes::kFreeInterface;
  const auto list = [](const char* text) {
    std::vector<double> v;
    std::stringstream ss(text);
    // "3x": the planner's cut-off (0 here; compare() resolves it).
    for (std::string item; std::getline(ss, item, ',');) v.push_back(item == "3x" ? 0.0 : std::atof(item.c_str()));
    return v;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool more = i + 1 < argc;
    if (a == "--duration-s" && more) {
      c.duration_s = std::atof(argv[++i]);
    } else if (a == "--fe-cache" && more) {
      cache_dir = argv[++i];
    } else if (a == "--frequencies-out" && more) {
      frequencies_out = argv[++i];
    } else if (a == "--partition") {
      partition_only = true;
    } else if (a == "--cost") {
      cost_only = true;
    } else if (a == "--train" && more) {
      c.train = argv[++i];
    } else if (a == "--vehicles" && more) {
      c.vehicles = std::atoi(argv[++i]);
    } else if (a == "--speed-kmh" && more) {
      c.speed_kmh = std::atof(argv[++i]);
    } else if (a == "--spans" && more) {
      c.spans_m = list(argv[++i]);
    } else if (a == "--approach-m" && more) {
      c.approach_m = std::atof(argv[++i]);
    } else if (a == "--no-profile") {
      c.profile = false;
    } else if (a == "--scene" && more) {
      c.scene_file = argv[++i];
    } else if (a == "--fixed-interface") {
      bridge_modes = railvsi::BridgeModes::kFixedInterface;
    } else if (a == "--dip") {
      c.dip = true;
    } else if (a == "--dip-depth-mm" && more) {
      c.dip = true;
      c.dip_depth_m = 1e-3 * std::atof(argv[++i]);
    } else if (a == "--dip-x-m" && more) {
      c.dip = true;
      c.dip_x_m = std::atof(argv[++i]);
    } else if (a == "--dip-length-m" && more) {
      c.dip = true;
      c.dip_length_m = std::atof(argv[++i]);
    } else if (a == "--cutoffs" && more) {
      cutoffs = list(argv[++i]);
    } else if (a == "--help" || a.empty() || a[0] == '-') {
      std::printf("hybrid_bench [DOFS ...] [--cutoffs 60,3x,...] [--dip] [--dip-depth-mm D] [--dip-x-m X] "
                  "[--dip-length-m L] [--speed-kmh V] [--train NAME] [--vehicles N] [--spans 25,25] [--approach-m A] "
                  "[--no-profile] [--scene FILE] [--duration-s T] [--fe-cache DIR] [--fixed-interface] [--partition] "
                  "[--cost [--frequencies-out PREFIX]]\n");
      return a == "--help" ? 0 : 2;
    } else {
      dofs.push_back(std::atoi(a.c_str()));
    }
  }
  if (dofs.empty()) dofs = c.scene_file.empty() ? std::vector<int>{6000, 20000} : std::vector<int>{0};
  for (int n : dofs) {
    if (partition_only) railvsi::partition(n);
    else if (cost_only) railvsi::cost(n, cutoffs, c.duration_s, c.train, bridge_modes, frequencies_out);
    else railvsi::compare(n, c, cutoffs, cache_dir, bridge_modes);
  }
  return 0;
}

// The standard EN 1991-2 HSLM check through the whole study service, as
// `vsi run --threads 1` runs it: HSLM-A1 to A10 x 101 speeds (100-400 km/h
// in steps of 3), 15 m simply supported span, f0 = 5 Hz, 15 t/m, 1 %
// damping, midspan; fidelity "auto" (the planner puts it on the modal
// moving-force rung, batched per train). Reported in one run, one core:
//   service    submit (expansion, planning, insert) + work (claim, run,
//              store) wall and process CPU time, jobs/s;
//   per job    the batched job path (run_jobs: scene, sweep, filter,
//              envelopes) timed in this thread, against
//   bare       the modal recurrence of the same jobs (their steps x modes
//              with their own modal steps, loads precomputed) in this thread.
// Run by hand: OPENBLAS_NUM_THREADS=1 build/tests/bench/modal_service_bench
//
// --service-only [--deck-alone] [--reps N]: only the service part of the
// study as a user runs it by default (no asks: the deck and the section
// forces), or with --deck-alone of the study that asks the deck alone
// (asks ["deck"]), N times (default 2) in this process, each on a new
// store; prints machine-readable lines (what tests/bench/peer_ratio reads):
//   rep K cpu_s C wall_s W jobs J failed F expand_s E submit_s S work_s K
//                                           (C: process CPU, all threads; E, S, K: wall)
//   model modes M dt_s D cutoff_hz H
//   peak TRAIN unfiltered_mps2 A at_kmh V filtered_mps2 A at_kmh V
// the peak lines being the largest midspan deck acceleration of each train
// over its speeds, as the last repetition's store holds it, unfiltered and
// after the code's low-pass filter.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/modal_moving_forces.hpp"
#include "core/freed_memory.hpp"
#include "core/huge_pages.hpp"
#include "cpu_time.hpp"
#include "envelopes/code_filter.hpp"
#include "integration/modal_recurrence.hpp"
#include "io/scene_loader.hpp"
#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/job_runner.hpp"
#include "workers/worker_pool.hpp"

namespace {

using namespace railvsi;
using namespace railvsi::scheduler;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

using bench::process_cpu_s;
using bench::thread_cpu_s;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

json hslm_study() {
  json trains = json::array();
  for (int a = 1; a <= 10; ++a) trains.push_back("HSLM-A" + std::to_string(a));
  return {{"name", "HSLM sweep, 15 m span"},
          {"structure",
           {{"generator", "bridge-2d"},
            {"spans_m", {15.0}},
            {"continuous", false},
            {"deck", {{"first_frequency_hz", 5.0}, {"mass_kg_per_m", 15000.0}}},
            {"damping", {{"ratio", 0.01}}},
            {"track", nullptr}}},
          {"trains", trains},
          {"speeds_kmh", {{"from", 100}, {"to", 400}, {"step", 3}}},
          {"analysis", json::object()},
          {"outputs", {{"points", {{{"name", "midspan"}, {"x_m", 7.5}}}}}},
          {"checks", {{"deck_acceleration_limit_mps2", 3.5}}}};
}

// The largest midspan deck acceleration of one train over its speeds.
struct TrainPeak {
  std::string train;
  double unfiltered_mps2 = 0.0, unfiltered_at_kmh = 0.0;
  double filtered_mps2 = 0.0, filtered_at_kmh = 0.0;
};

// One pass of the service (submit + work + store) and what the store holds.
struct ServiceRun {
  StudyPlan plan;
  double expand_s = 0.0, submit_s = 0.0, service_s = 0.0, service_cpu_s = 0.0;
  WorkSummary work;
  double job_wall_s = 0.0, loop_s = 0.0, basis_s = 0.0, min_cutoff_hz = 0.0, max_cutoff_hz = 0.0;
  long jobs = 0, steps = 0;
  std::string rung, fidelity;
  std::vector<TrainPeak> peaks;
};

ServiceRun run_service(const json& doc) {
  const auto db_file = std::filesystem::temp_directory_path() / ("modal-service-bench-" + std::to_string(::getpid()) + ".sqlite");
  const auto remove_db = [&] {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db_file.string() + suffix);
  };
  remove_db();

  // 1. The service: submit + work + store.
  ServiceRun r;
  const double cpu0 = process_cpu_s();
  const auto t0 = Clock::now();
  r.plan = expand_study(doc, std::filesystem::current_path(), "bench-study.json");
  r.expand_s = since(t0);
  {
    // As `vsi run`: the submitting connection stays open while the workers
    // run (so the store is checkpointed once, when it closes, not also
    // between submit and work), and its close is timed.
    Database db(db_file.string());
    migrate(db);
    submit_study(db, r.plan);
    r.submit_s = since(t0);
    WorkOptions o;
    o.db_file = db_file.string();
    o.threads = 1;
    r.work = run_workers(o);
  }
  r.service_s = since(t0);
  r.service_cpu_s = process_cpu_s() - cpu0;
  {
    Database db(db_file.string());
    Statement s = db.prepare("SELECT count(*), total(wall_s), total(loop_s), total(steps), total(factorization_s), "
                             "min(rung), max(fidelity), min(cutoff_hz), max(cutoff_hz) FROM job_records "
                             "WHERE state = 'done'");
    s.step();
    r.jobs = s.int64(0);
    r.job_wall_s = s.real(1);
    r.loop_s = s.real(2);
    r.steps = static_cast<long>(s.real(3));
    r.basis_s = s.real(4);
    r.rung = s.text(5);
    r.fidelity = s.text(6);
    r.min_cutoff_hz = s.real(7);
    r.max_cutoff_hz = s.real(8);
    // Per train, the largest value over its speeds and the speed of it (the
    // row of max() gives the bare column in SQLite); A1 ... A10 in order.
    const auto peaks = [&](const char* quantity, auto on_row) {
      Statement q = db.prepare("SELECT train, max(value), speed_kmh FROM study_envelopes WHERE quantity = ?1 AND "
                               "location = 'midspan' GROUP BY train ORDER BY length(train), train");
      q.bind(1, quantity);
      for (std::size_t i = 0; q.step(); ++i) on_row(i, q.text(0), q.real(1), q.real(2));
    };
    peaks("deck_acceleration_unfiltered_mps2", [&](std::size_t, const std::string& train, double a, double v) {
      r.peaks.push_back({train, a, v, 0.0, 0.0});
    });
    peaks("deck_acceleration_mps2", [&](std::size_t i, const std::string& train, double a, double v) {
      if (i >= r.peaks.size() || r.peaks[i].train != train) throw std::runtime_error("filtered peaks: train order");
      r.peaks[i].filtered_mps2 = a;
      r.peaks[i].filtered_at_kmh = v;
    });
  }
  remove_db();
  return r;
}

// One measurement of the service and the per-job path for this study.
void measure(const json& doc, const char* label) {
  const ServiceRun sr = run_service(doc);
  const StudyPlan& plan = sr.plan;
  const double expand_s = sr.expand_s, submit_s = sr.submit_s, service_s = sr.service_s;
  const double service_cpu_s = sr.service_cpu_s;
  const WorkSummary& work = sr.work;
  const double job_wall_s = sr.job_wall_s, loop_s = sr.loop_s, basis_s = sr.basis_s;
  const long jobs = sr.jobs, steps = sr.steps;
  const std::string& rung = sr.rung;
  const std::string& fidelity = sr.fidelity;
  const json f = json::parse(fidelity);
  const int modes = f.at("modes").get<int>();
  const double dt = f.at("dt_s").get<double>();

  // 2. The per-job path in this thread: the batches as the worker runs them.
  std::map<std::string, std::vector<ClaimedJob>> batches;
  for (const JobSpec& j : plan.jobs)
    batches[j.train].push_back({j.id, j.scene, j.operator_key, j.train, j.irregularity, j.speed_kmh, j.dt_s, j.cutoff_hz, 1, j.rung});
  FactorizationCache cache;
  double sink = 0.0;
  long path_steps = 0;
  const double tp = thread_cpu_s();
  for (const auto& [train, batch] : batches)
    for (const JobOutcome& out : run_jobs(batch, cache)) path_steps += out.steps;
  const double path_s = thread_cpu_s() - tp;

  // Where the per-job path goes: the sweep's time loop and the code filter,
  // timed apart on the same jobs and in the same groups of speeds as the
  // job path (scene parsed once per train); and the time loop one job at a
  // time (one lane), for comparison.
  double sweep_s = 0.0, filter_s = 0.0, single_s = 0.0;
  for (const auto& [train, batch] : batches) {
    const Scene scene = parse_scene(json::parse(batch.front().scene), "/", "job");
    ModalBasisOptions mo;
    mo.max_frequency_hz = scene.fidelity.modal_cutoff_hz.value();
    const ModalBasis basis(scene.structure, mo);
    const auto& rails = scene.analysis.contact.rail_lines;
    const bool sections = !doc.contains("asks") || doc.at("asks").dump().find("section_forces") != std::string::npos;
    const ModalSweep sweep(basis, scene.train, rails, scene.analysis.dt_s,
                           sections ? modal_section_forces(basis, rails) : nullptr);
    const CodeFilter filter(scene.analysis.dt_s, batch.front().cutoff_hz);
    ModalSweepWorkspace ws;
    CodeFilter::LaneWorkspace fws;
    for (std::size_t first = 0; first < batch.size(); first += kSweepLanes) {
      std::vector<SweepLane> lanes;
      for (std::size_t j = first; j < std::min(batch.size(), first + kSweepLanes); ++j) {
        Scene at = scene;
        at.speed_mps = batch[j].speed_kmh / 3.6;
        lanes.push_back({modal_run_start_x_m(at), at.speed_mps, modal_run_steps(at)});
      }
      const double t1 = thread_cpu_s();
      const std::vector<ModalSweepRun> runs = sweep.run_group(lanes, ws);
      const double t2 = thread_cpu_s();
      std::vector<const std::vector<double>*> signals;
      for (std::size_t g = 0; g < lanes.size(); ++g) signals.push_back(&ws.acceleration[g][0]);
      double maxima[CodeFilter::kLanes];
      filter.max_abs_filtered(signals, maxima, fws);
      filter_s += thread_cpu_s() - t2;
      sweep_s += t2 - t1;
      for (std::size_t g = 0; g < lanes.size(); ++g) sink += maxima[g] + static_cast<double>(runs[g].steps);
      const double t3 = thread_cpu_s();
      for (const SweepLane& l : lanes) sink += static_cast<double>(sweep.run(l.x0_m, l.speed_mps, l.n_steps, ws).steps);
      single_s += thread_cpu_s() - t3;
    }
  }

  // 3. The bare recurrence of the same steps with as many modal steps.
  std::vector<ModalStep> ms;
  for (int k = 0; k < modes; ++k) {
    // Simply supported span: f_k = k^2 f0 (the modes the basis holds to within the mesh's error).
    const double w = 2.0 * std::numbers::pi * 5.0 * (k + 1) * (k + 1);
    ms.push_back(make_modal_step(w, 0.01, dt));
  }
  std::vector<double> load(4096);
  for (std::size_t i = 0; i < load.size(); ++i) load[i] = 1e3 * std::sin(0.01 * static_cast<double>(i));
  std::vector<double> q(static_cast<std::size_t>(modes), 0.0), qd(q);
  const double tb = thread_cpu_s();
  for (long n = 0; n < path_steps; ++n) {
    const double p0 = load[static_cast<std::size_t>(n) & 4095], p1 = load[static_cast<std::size_t>(n + 1) & 4095];
    for (int k = 0; k < modes; ++k) sink += ms[static_cast<std::size_t>(k)].advance(q[k], qd[k], p0, p1);
  }
  const double bare_s = thread_cpu_s() - tb;

  std::printf("HSLM sweep through the service, %s (%s, %d modes, dt %.3g s): %ld jobs, %ld steps\n", label,
              rung.c_str(), modes, dt, jobs, steps);
  std::printf("  service: %.3f s wall (%.3f s CPU, all threads) = submit %.3f s (expansion %.3f s) + work %.3f s; "
              "%.0f jobs/s; failed %lld\n",
              service_s, service_cpu_s, submit_s, expand_s, work.wall_s, jobs / service_s,
              static_cast<long long>(work.jobs_failed));
  std::printf("  work: jobs %.3f s (loops %.3f s, envelopes and scene %.3f s, modes %.4f s); claims, commits, "
              "progress %.3f s\n",
              job_wall_s, loop_s, job_wall_s - loop_s, basis_s, work.wall_s - job_wall_s);
  std::printf("  per job (this thread): path %.3f s = %.1f us/job; bare recurrence %.4f s = %.1f us/job; "
              "path / bare = %.2f (sink %g)\n",
              path_s, 1e6 * path_s / jobs, bare_s, 1e6 * bare_s / jobs, path_s / bare_s, sink);
  std::printf("  of the path: time loop in groups of %d speeds (loads, recurrence, outputs, section forces if asked) "
              "%.1f us/job = %.2f x bare; code filter %.1f us/job = %.2f x bare; the rest (scene, summary, envelopes) "
              "%.1f us/job\n",
              kSweepLanes, 1e6 * sweep_s / jobs, sweep_s / bare_s, 1e6 * filter_s / jobs, filter_s / bare_s,
              1e6 * (path_s - sweep_s - filter_s) / jobs);
  std::printf("  the time loop one speed at a time: %.1f us/job = %.2f x bare\n", 1e6 * single_s / jobs,
              single_s / bare_s);
}

json deck_only_study() {
  json deck_only = hslm_study();
  deck_only["asks"] = {"deck"};
  return deck_only;
}

// --service-only: the default (or deck-alone) study's service, reps times, machine-readable.
int service_only(int reps, bool deck_alone) {
  ServiceRun last;
  for (int k = 1; k <= reps; ++k) {
    last = run_service(deck_alone ? deck_only_study() : hslm_study());
    std::printf("rep %d cpu_s %.4f wall_s %.4f jobs %ld failed %lld expand_s %.4f submit_s %.4f work_s %.4f\n", k,
                last.service_cpu_s, last.service_s, last.jobs, static_cast<long long>(last.work.jobs_failed),
                last.expand_s, last.submit_s, last.work.wall_s);
  }
  const json f = json::parse(last.fidelity);
  std::printf("model modes %d dt_s %.6g cutoff_hz %.6g %.6g\n", f.at("modes").get<int>(), f.at("dt_s").get<double>(),
              last.min_cutoff_hz, last.max_cutoff_hz);
  for (const TrainPeak& p : last.peaks)
    std::printf("peak %s unfiltered_mps2 %.6f at_kmh %g filtered_mps2 %.6f at_kmh %g\n", p.train.c_str(),
                p.unfiltered_mps2, p.unfiltered_at_kmh, p.filtered_mps2, p.filtered_at_kmh);
  return last.jobs > 0 && last.work.jobs_failed == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // The process as vsi sets it up: huge pages for the heap, freed buffers
  // kept, one heap for the worker threads.
  reexec_with_huge_pages(argv);
  keep_freed_memory();
  one_heap_for_all_threads();
  single_threaded_blas();
  bool only_service = false, deck_alone = false;
  int reps = 2;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--service-only") == 0) {
      only_service = true;
    } else if (std::strcmp(argv[i], "--deck-alone") == 0) {
      deck_alone = true;
    } else if (std::strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
      reps = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: modal_service_bench [--service-only [--deck-alone] [--reps N]]\n");
      return 2;
    }
  }
  if (only_service) {
    if (reps < 1) {
      std::fprintf(stderr, "modal_service_bench: --reps must be at least 1\n");
      return 2;
    }
    return service_only(reps, deck_alone);
  }
  // The study's checks ask the deck; a study without asks gets the section
  // forces too (what the report's dynamic increments need) ...
  measure(hslm_study(), "deck and section forces (default)");
  // ... and one that asks the deck alone skips them.
  measure(deck_only_study(), "deck alone (asks [\"deck\"])");
  return 0;
}

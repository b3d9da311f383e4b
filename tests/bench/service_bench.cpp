// Study service benchmarks: whole studies through the queue and one worker
// thread, as `vsi run --threads 1` runs them. Reported per study:
//   jobs_per_s       jobs finished per second of wall time (submission excluded)
//   factorizations   structure factorizations (= distinct operator keys)
//   job_overhead     time of the jobs beyond their time loops (scene parsing,
//                    static equilibrium, factorization, envelopes) / time loops
//   service_overhead wall time beyond the time loops (also claims, commits,
//                    heartbeat) / time loops
//   submit_s         expansion and validation of the study, and the insert
// Run by hand: OPENBLAS_NUM_THREADS=1 build/tests/bench/service_bench
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "io/json_document.hpp"
#include "queue/job_queue.hpp"
#include "store/sqlite.hpp"
#include "store/store_schema.hpp"
#include "study/study_plan.hpp"
#include "workers/worker_pool.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

const std::filesystem::path kExamples = std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs" / "examples";

// The HSLM example study with 100 speeds: 10 trains x 100 = 1,000 jobs.
json hslm_study() {
  json doc = read_json_file(kExamples / "hslm-sweep.json");
  doc["speeds_kmh"] = {{"from", 100}, {"to", 397}, {"step", 3}};
  return doc;
}

// Three multibody trains x 50 speeds with nonlinear Hertz contact on the
// example viaduct (three 25 m spans, ballasted track, irregularity profile).
json multibody_study() {
  const json scene = read_json_file(kExamples / "viaduct-ice3.json");
  json doc;
  doc["name"] = "multibody on the viaduct";
  for (const char* key : {"structure", "irregularity", "analysis", "outputs"}) doc[key] = scene.at(key);
  doc["irregularities"] = json::array({doc["irregularity"]});
  doc.erase("irregularity");
  doc["analysis"].erase("dt_s");  // the time-step policy chooses
  doc["trains"] = json::array({"ICE3", "Eurostar", "Shinkansen300"});
  doc["speeds_kmh"] = {{"from", 150}, {"to", 395}, {"step", 5}};
  return doc;
}

void run_study(benchmark::State& state, const json& doc) {
  single_threaded_blas();
  const auto db_file = std::filesystem::temp_directory_path() / ("service-bench-" + std::to_string(::getpid()) + ".sqlite");
  for (auto _ : state) {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db_file.string() + suffix);
    const auto t0 = Clock::now();
    const StudyPlan plan = expand_study(doc, kExamples, "bench-study.json");
    {
      Database db(db_file.string());
      migrate(db);
      submit_study(db, plan);
    }
    const double submit_s = std::chrono::duration<double>(Clock::now() - t0).count();
    WorkOptions options;
    options.db_file = db_file.string();
    options.threads = 1;
    const WorkSummary work = run_workers(options);

    Database db(db_file.string());
    Statement s = db.prepare("SELECT count(*), total(wall_s), total(loop_s), total(steps) FROM jobs WHERE state = 'done'");
    s.step();
    const double jobs = static_cast<double>(s.int64(0)), job_wall_s = s.real(1), loop_s = s.real(2);
    state.SetIterationTime(work.wall_s);
    state.counters["jobs"] = jobs;
    state.counters["failed"] = static_cast<double>(work.jobs_failed);
    state.counters["jobs_per_s"] = jobs / work.wall_s;
    state.counters["factorizations"] = static_cast<double>(work.cache.factorizations);
    state.counters["factorization_s"] = work.cache.factorization_s;
    state.counters["steps_per_job"] = s.real(3) / jobs;
    state.counters["job_overhead"] = (job_wall_s - loop_s) / loop_s;
    state.counters["service_overhead"] = (work.wall_s - loop_s) / loop_s;
    state.counters["submit_s"] = submit_s;
  }
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db_file.string() + suffix);
}

void BM_HslmSweep1000Jobs(benchmark::State& state) { run_study(state, hslm_study()); }
void BM_MultibodyViaduct150Jobs(benchmark::State& state) { run_study(state, multibody_study()); }

BENCHMARK(BM_HslmSweep1000Jobs)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_MultibodyViaduct150Jobs)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace
}  // namespace railvsi::scheduler

BENCHMARK_MAIN();

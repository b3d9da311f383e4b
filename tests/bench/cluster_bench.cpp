// The viaduct interaction study (ICE3, Eurostar, Shinkansen300 as multibody
// trains with nonlinear Hertz contact over three 25 m spans with track and
// the example profile) run through a real single-node Slurm as 1 and as 2
// array tasks (vsi slurm --submit, one CPU per task), each followed by the
// merge job. Prints the wall times, their ratio, and the overhead of shard
// + merge as a share of the total. Run by hand, as root, with the Slurm
// packages of tests/setup installed:
//   build/tests/bench/cluster_bench [speeds]     (default 50: 150 jobs, long)
// The speeds are spread evenly over 150-395 km/h. Not a ctest test.
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <regex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../cluster/slurm_cluster.hpp"
#include "io/json_document.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
const fs::path kExamples = fs::path(RAILVSI_SOURCE_DIR) / "jobs" / "examples";

json viaduct_study(int speeds) {
  const json scene = read_json_file(kExamples / "viaduct-ice3.json");
  json doc;
  doc["name"] = fmt::format("multibody on the viaduct, {} speeds", speeds);
  for (const char* key : {"structure", "analysis", "outputs"}) doc[key] = scene.at(key);
  json profile = scene.at("irregularity");
  if (profile.contains("csv")) profile["csv"] = (kExamples / profile["csv"].get<std::string>()).string();
  doc["irregularities"] = json::array({profile});
  doc["analysis"].erase("dt_s");  // the time-step policy chooses
  doc["trains"] = json::array({"ICE3", "Eurostar", "Shinkansen300"});
  json list = json::array();
  for (int i = 0; i < speeds; ++i) list.push_back(speeds == 1 ? 150.0 : 150.0 + 245.0 * i / (speeds - 1));
  doc["speeds_kmh"] = list;
  return doc;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Run {
  double total_s = 0, shard_s = 0, merge_s = 0;
};

Run run_array(const fs::path& dir, const fs::path& study, int tasks) {
  const fs::path out = dir / fmt::format("tasks-{}", tasks);
  Run r;
  const auto t0 = Clock::now();
  const std::string submitted = sh(fmt::format("{} slurm {} --shards {} --out {} --submit", VSI_BINARY, study.string(),
                                               tasks, out.string()));
  r.shard_s = seconds_since(t0);
  std::smatch m;
  if (!std::regex_search(submitted, m, std::regex("merge job ([0-9]+)")))
    throw std::runtime_error("vsi slurm failed: " + submitted);
  const std::string merge = m[1].str();
  if (!wait_until([&] { return SlurmCluster::job_field(merge, "JobState") == "COMPLETED"; }, std::chrono::hours(2),
                  std::chrono::milliseconds(500)))
    throw std::runtime_error("the merge job did not complete: " + sh("scontrol show job " + merge));
  r.total_s = seconds_since(t0);
  // The merge again into a fresh file: the merge job's own time.
  const auto t1 = Clock::now();
  sh(fmt::format("{} merge {}/shard-*.sqlite --into {}/again.sqlite", VSI_BINARY, out.string(), out.string()));
  r.merge_s = seconds_since(t1);
  std::cout << sh(fmt::format("{} status --db {}/results.sqlite", VSI_BINARY, out.string()));
  return r;
}

}  // namespace
}  // namespace railvsi::test

int main(int argc, char** argv) {
  using namespace railvsi::test;
  const int speeds = argc > 1 ? std::atoi(argv[1]) : 50;
  const fs::path dir = fs::temp_directory_path() / fmt::format("vsi-cluster-bench-{}", ::getpid());
  fs::create_directories(dir);
  int code = 0;
  {
    SlurmCluster cluster;
    if (const std::string why = cluster.start(); !why.empty()) {
      std::cerr << "cannot start Slurm: " << why << '\n';
      return 1;
    }
    const fs::path study = dir / "study.json";
    std::ofstream(study) << viaduct_study(speeds).dump(2);
    try {
      const Run one = run_array(dir, study, 1);
      const Run two = run_array(dir, study, 2);
      std::cout << fmt::format("viaduct study, 3 trains x {} speeds ({} jobs)\n", speeds, 3 * speeds);
      std::cout << "| array tasks | wall s | shard + submit s | merge s | shard + merge share |\n|---|---|---|---|---|\n";
      for (const auto& [tasks, r] : {std::pair{1, one}, std::pair{2, two}})
        std::cout << fmt::format("| {} | {:.1f} | {:.2f} | {:.2f} | {:.2f} % |\n", tasks, r.total_s, r.shard_s,
                                 r.merge_s, 100.0 * (r.shard_s + r.merge_s) / r.total_s);
      std::cout << fmt::format("wall time ratio 1 task / 2 tasks: {:.2f}\n", one.total_s / two.total_s);
    } catch (const std::exception& e) {
      std::cerr << e.what() << '\n';
      code = 1;
    }
  }
  fs::remove_all(dir);
  return code;
}

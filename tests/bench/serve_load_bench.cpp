// vsi serve under load: 100 clients ask GET /api/studies/ID at once, five
// times, while the server's worker runs a multibody study (about a second a
// job). Prints p50 and p99 of the request latency, and their ratios to the
// floor measured in the same run: the same request asked by one client at a
// time (100 times) on the same busy server. Run by hand:
//   build/tests/bench/serve_load_bench [clients]     (default 100)
// Not a ctest test.
#include <algorithm>
#include <barrier>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../service/serve_process.hpp"
#include "../service/served_studies.hpp"

namespace railvsi::test {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

int run(int clients) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "vsi-serve-load-bench";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ServeProcess server({"--db", (dir / "store.sqlite").string(), "--threads", "1"}, dir);
  if (!server.running()) {
    std::fprintf(stderr, "vsi serve did not start: %s\n", server.log().c_str());
    return 1;
  }
  const json study = multibody_study("load bench: ICE3 multibody", 20);
  const auto posted = server.client()->Post("/api/studies", study.dump(), "application/json");
  if (!posted || posted->status != 202) return 1;
  const std::string path = "/api/studies/" + json::parse(posted->body)["id"].get<std::string>();
  std::this_thread::sleep_for(std::chrono::seconds(2));  // the worker is running a job

  // Floor: one client, one request at a time.
  std::vector<double> floor_ms;
  {
    const auto c = server.client();
    for (int i = 0; i < 100; ++i) {
      const auto t0 = Clock::now();
      const auto r = c->Get(path.c_str());
      if (!r || r->status != 200) return 1;
      floor_ms.push_back(ms_since(t0));
    }
  }
  // Load: `clients` threads, each its own connection, released together.
  std::vector<double> load_ms;
  int failures = 0;
  for (int round = 0; round < 5; ++round) {
    std::vector<double> ms(clients, -1.0);
    std::barrier start(clients);
    std::vector<std::jthread> threads;
    for (int i = 0; i < clients; ++i)
      threads.emplace_back([&, i] {
        httplib::Client c("127.0.0.1", server.port());
        c.set_read_timeout(std::chrono::seconds(60));
        start.arrive_and_wait();
        const auto t0 = Clock::now();
        const auto r = c.Get(path.c_str());
        if (r && r->status == 200) ms[i] = ms_since(t0);
      });
    threads.clear();
    for (double m : ms) (m < 0 ? ++failures : (load_ms.push_back(m), 0));
  }
  const json status = json::parse(server.client()->Get(path.c_str())->body);
  const double f50 = percentile(floor_ms, 0.5), p50 = percentile(load_ms, 0.5), p99 = percentile(load_ms, 0.99);
  std::printf("floor (1 client, 100 sequential requests): p50 %.2f ms, p99 %.2f ms\n", f50, percentile(floor_ms, 0.99));
  std::printf("%d concurrent clients x 5 rounds (%zu answered, %d failed): p50 %.2f ms, p99 %.2f ms, max %.2f ms\n",
              clients, load_ms.size(), failures, p50, p99, percentile(load_ms, 1.0));
  std::printf("ratios to the floor's p50: p50 %.1f, p99 %.1f; the study meanwhile: %d of %d jobs done\n", p50 / f50,
              p99 / f50, status["jobs"]["done"].get<int>(), status["jobs"]["total"].get<int>());
  server.stop(SIGTERM);
  std::filesystem::remove_all(dir);
  return failures == 0 ? 0 : 1;
}

}  // namespace
}  // namespace railvsi::test

int main(int argc, char** argv) { return railvsi::test::run(argc > 1 ? std::atoi(argv[1]) : 100); }

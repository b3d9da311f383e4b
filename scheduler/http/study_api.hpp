#pragma once
// vsi serve's HTTP API over a study store (schemas/http-api.openapi.json).
// Every route runs the code of the command it stands for: submit, status,
// query, report, cancel, retry (cli/service_commands.hpp); this file only
// maps requests to their arguments and their results to HTTP.
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/service_commands.hpp"
#include "store/sqlite.hpp"

namespace httplib {
class Server;
}

namespace railvsi::scheduler {

struct StudyApiOptions {
  cli::ServiceArgs service;  // the store (service.db) and the submit options
  // Empty: no check. Else every /api request needs "Authorization: Bearer <token>".
  std::string token;
  std::size_t max_body_bytes = std::size_t{16} << 20;  // larger bodies: 413
};

class StudyApi {
 public:
  explicit StudyApi(StudyApiOptions options);
  // Adds the routes, the token check and the error bodies to `server`.
  void mount(httplib::Server& server);

 private:
  // vsi status's figures of one study as JSON, with the checks' verdict
  // once no job is left to run.
  nlohmann::ordered_json study_json(Database& db, const std::string& id);

  StudyApiOptions options_;
  std::mutex submit_mutex_;  // one submit at a time: each expands a study and writes the store
  // The verdict of a finished study judges all its jobs: kept per study for
  // as long as its counts of done, failed and cancelled jobs stay the same
  // (every dashboard asks for it every 2 s).
  struct KnownVerdict {
    std::int64_t done = -1, failed = -1, cancelled = -1;
    std::string verdict, error;
  };
  std::mutex verdicts_mutex_;
  std::map<std::string, KnownVerdict> verdicts_;
};

}  // namespace railvsi::scheduler

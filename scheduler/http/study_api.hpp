#pragma once
// vsi serve's HTTP API over a study store (schemas/http-api.openapi.json).
// Every route runs the code of the command it stands for: submit, status,
// query, report, cancel, retry (cli/service_commands.hpp); this file only
// maps requests to their arguments and their results to HTTP.
#include <cstddef>
#include <mutex>
#include <string>

#include "cli/service_commands.hpp"

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
  StudyApiOptions options_;
  std::mutex submit_mutex_;  // one submit at a time: each expands a study and writes the store
};

}  // namespace railvsi::scheduler

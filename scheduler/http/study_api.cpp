#include "http/study_api.hpp"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/report_command.hpp"
#include "cli/service_store.hpp"
#include "cli/verdict_exit.hpp"
#include "core/input_error.hpp"
#include "core/sha256.hpp"
#include "http/bearer_token.hpp"
#include "http/dashboard_page.hpp"
#include "query/study_report.hpp"
#include "query/study_results.hpp"
#include "query/study_status.hpp"
#include "queue/job_queue.hpp"
#include "store/store_schema.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::ordered_json;

void send_json(httplib::Response& res, int status, const ordered_json& body) {
  res.status = status;
  res.set_content(body.dump(2) + "\n", "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, {{"error", message}});
}

// A read connection for the status routes. Without open_store's
// PRAGMA quick_check, which reads the whole file at every request (the
// server checked the store when it started; vsi check examines it).
std::unique_ptr<Database> read_store(const std::string& file) {
  auto db = std::make_unique<Database>(file, OpenMode::kReadOnly);
  require_current_schema(*db);
  return db;
}

// The study a path's ID names (a unique prefix of at least 6 digits is
// enough, as on the command line); empty, with a 404 sent, when none.
std::string study_of(Database& db, const std::string& id, httplib::Response& res) {
  const std::string full = id.size() >= 6 ? resolve_study_id(db, id) : std::string();
  if (full.empty()) send_error(res, 404, "no study " + id + " in this store");
  return full;
}

// The body of POST /api/studies, kept beside the store under the SHA-256 of
// its bytes: the same study posted again is the same file. Files a study
// names (trains, profiles) are found relative to this folder.
std::filesystem::path keep_upload(const std::string& db_file, const std::string& body) {
  const std::filesystem::path dir = std::filesystem::absolute(db_file).parent_path() / "vsi-uploads";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / (sha256_hex(body) + ".json");
  if (std::filesystem::exists(file)) return file;
  const std::filesystem::path part = dir / (file.filename().string() + "." + std::to_string(::getpid()) + ".part");
  std::ofstream(part, std::ios::binary) << body;
  std::filesystem::rename(part, file);  // whole or absent: a concurrent reader never sees half
  return file;
}

}  // namespace

StudyApi::StudyApi(StudyApiOptions options) : options_(std::move(options)) {}

ordered_json StudyApi::study_json(Database& db, const std::string& id) {
  const StudyStatus s = study_status(db, id);
  const StateCounts& c = s.counts;
  ordered_json out = {{"id", s.id},
                      {"name", s.name},
                      {"jobs",
                       {{"total", c.total()},
                        {"queued", c.queued},
                        {"running", c.running},
                        {"done", c.done},
                        {"failed", c.failed},
                        {"cancelled", c.cancelled},
                        {"stale_leases", s.stale_leases}}},
                      {"throughput_jobs_per_s", s.jobs_per_s ? ordered_json(*s.jobs_per_s) : ordered_json(nullptr)},
                      {"eta_s", s.eta_s && c.unfinished() > 0 ? ordered_json(*s.eta_s) : ordered_json(nullptr)},
                      {"verdict", nullptr}};
  if (c.unfinished() == 0 && c.total() > 0) {
    KnownVerdict known;
    {
      const std::lock_guard lock(verdicts_mutex_);
      known = verdicts_[id];
    }
    if (known.done != c.done || known.failed != c.failed || known.cancelled != c.cancelled) {
      known = {c.done, c.failed, c.cancelled, {}, {}};
      try {
        known.verdict = verdict_name(cli::judge_jobs(db, id, study_results(db, {id, {}, {}, {}, {}, {}})).overall);
      } catch (const InputError& e) {  // a stored scene that no longer loads: as vsi query, no verdict
        known.error = e.describe();
      }
      const std::lock_guard lock(verdicts_mutex_);
      verdicts_[id] = known;
    }
    if (!known.verdict.empty()) out["verdict"] = known.verdict;
    if (!known.error.empty()) out["verdict_error"] = known.error;
  }
  return out;
}

void StudyApi::mount(httplib::Server& server) {
  server.set_payload_max_length(options_.max_body_bytes);
  server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (options_.token.empty() || !req.path.starts_with("/api/")) return httplib::Server::HandlerResponse::Unhandled;
    if (bearer_matches(req.get_header_value("Authorization"), options_.token))
      return httplib::Server::HandlerResponse::Unhandled;
    res.set_header("WWW-Authenticate", "Bearer");
    send_error(res, 401, "this server needs its token: Authorization: Bearer <token>");
    return httplib::Server::HandlerResponse::Handled;
  });
  // Status codes the library sets itself (404 of an unknown route, 413) get a JSON body.
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    send_error(res, res.status,
               res.status == 413   ? "request body too large"
               : res.status == 404 ? "no such resource: " + req.path
                                   : "HTTP status " + std::to_string(res.status));
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr e) {
    try {
      std::rethrow_exception(e);
    } catch (const InputError& error) {
      send_error(res, 400, error.describe());
    } catch (const std::exception& error) {
      send_error(res, 500, error.what());
    } catch (...) {
      send_error(res, 500, "unexpected failure");
    }
  });

  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(std::string(dashboard_html()), "text/html; charset=utf-8");
  });

  server.Post("/api/studies", [this](const httplib::Request& req, httplib::Response& res) {
    const std::lock_guard lock(submit_mutex_);
    cli::ServiceArgs args = options_.service;
    args.study_file = keep_upload(args.db, req.body).string();
    try {
      const SubmitResult r = cli::submit_study_file(args);
      send_json(res, 202, {{"id", r.study_id}, {"jobs", r.jobs}, {"new_jobs", r.new_jobs}});
    } catch (const InputError& e) {
      std::filesystem::remove(args.study_file);  // only studies that were queued are kept
      // vsi validate's path and message; the kept file's name is the server's business.
      send_json(res, 400,
                {{"error", (e.json_path().empty() ? std::string("/") : e.json_path()) + ": " + e.what()},
                 {"path", e.json_path().empty() ? std::string("/") : e.json_path()},
                 {"message", e.what()}});
    }
  });

  server.Get("/api/studies", [this](const httplib::Request&, httplib::Response& res) {
    const auto db = read_store(options_.service.db);
    ordered_json list = ordered_json::array();
    for (const std::string& id : study_ids(*db)) list.push_back(study_json(*db, id));
    send_json(res, 200, {{"studies", std::move(list)}});
  });

  server.Get(R"(/api/studies/([0-9a-f]+))", [this](const httplib::Request& req, httplib::Response& res) {
    const auto db = read_store(options_.service.db);
    const std::string id = study_of(*db, req.matches[1], res);
    if (!id.empty()) send_json(res, 200, study_json(*db, id));
  });

  server.Get(R"(/api/studies/([0-9a-f]+)/envelopes)", [this](const httplib::Request& req, httplib::Response& res) {
    cli::ServiceArgs args = options_.service;
    {
      const auto db = cli::open_store(args.db);
      args.study_id = study_of(*db, req.matches[1], res);
      if (args.study_id.empty()) return;
    }
    args.format = req.has_param("format") ? req.get_param_value("format") : "json";
    if (args.format != "json" && args.format != "csv" && args.format != "table")
      return send_error(res, 400, "format: give json, csv or table");
    if (req.has_param("train")) args.train = req.get_param_value("train");
    if (req.has_param("irregularity")) args.irregularity = req.get_param_value("irregularity");
    try {
      if (req.has_param("speed_min")) args.speed_min_kmh = std::stod(req.get_param_value("speed_min"));
      if (req.has_param("speed_max")) args.speed_max_kmh = std::stod(req.get_param_value("speed_max"));
    } catch (const std::exception&) {
      return send_error(res, 400, "speed_min, speed_max: give numbers in km/h");
    }
    args.wide = req.has_param("wide") && req.get_param_value("wide") == "true";
    if (req.has_param("structure")) args.structure = req.get_param_value("structure");  // a bridge of a line study
    std::ostringstream out, err;
    if (cli::write_query(args, out, err) != cli::kExitOk) return send_error(res, 400, err.str());
    const char* type = args.format == "json" ? "application/json" : args.format == "csv" ? "text/csv" : "text/plain";
    res.set_content(out.str(), std::string(type) + "; charset=utf-8");
  });

  server.Get(R"(/api/studies/([0-9a-f]+)/report)", [this](const httplib::Request& req, httplib::Response& res) {
    cli::ReportArgs args;
    args.db = options_.service.db;
    {
      const auto db = cli::open_store(args.db);
      args.study_id = study_of(*db, req.matches[1], res);
      if (args.study_id.empty()) return;
    }
    static std::atomic<unsigned> serial{0};  // one file per request: reports may be made side by side
    args.out = (std::filesystem::temp_directory_path() /
                ("vsi-serve-report-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + ".html"))
                   .string();
    const int code = cli::report_command(args);
    std::ifstream in(args.out, std::ios::binary);
    std::ostringstream html;
    html << in.rdbuf();
    std::filesystem::remove(args.out);
    if (code != cli::kExitOk || html.str().empty()) return send_error(res, 500, "the report could not be made (server log)");
    res.set_content(html.str(), "text/html; charset=utf-8");
  });

  server.Post(R"(/api/studies/([0-9a-f]+)/cancel)", [this](const httplib::Request& req, httplib::Response& res) {
    const auto db = cli::open_store(options_.service.db, OpenMode::kExisting);
    const std::string id = study_of(*db, req.matches[1], res);
    if (id.empty()) return;
    const CancelResult c = cancel_study(*db, id);  // as vsi cancel: jobs another unfinished study needs stay
    send_json(res, 200, {{"id", id}, {"cancelled", c.cancelled}, {"left_for_other_studies", c.left_for_other_studies}});
  });
  server.Post(R"(/api/studies/([0-9a-f]+)/retry)", [this](const httplib::Request& req, httplib::Response& res) {
    const auto db = cli::open_store(options_.service.db, OpenMode::kExisting);
    const std::string id = study_of(*db, req.matches[1], res);
    if (!id.empty()) send_json(res, 200, {{"id", id}, {"queued", retry_study(*db, id)}});
  });

  server.Get(R"(/api/jobs/([0-9a-f]+))", [this](const httplib::Request& req, httplib::Response& res) {
    const std::string prefix = req.matches[1];
    if (prefix.size() < 6) return send_error(res, 404, "no job " + prefix + " (give at least 6 digits of its id)");
    const auto db = cli::open_store(options_.service.db);
    Statement s = db->prepare(
        "SELECT j.id, sj.study_id FROM jobs j JOIN study_jobs sj ON sj.job_id = j.id "
        "WHERE substr(j.id, 1, ?) = ? ORDER BY j.id LIMIT 2");
    s.bind(1, static_cast<std::int64_t>(prefix.size())).bind(2, prefix);
    if (!s.step()) return send_error(res, 404, "no job " + prefix + " in this store");
    const std::string job_id = s.text(0), study_id = s.text(1);
    if (s.step() && s.text(0) != job_id) return send_error(res, 400, "job id prefix " + prefix + " is ambiguous");
    for (const JobResult& job : study_results(*db, {study_id, {}, {}, {}, {}, {}}))
      if (job.id == job_id) {
        ordered_json out = format_json(study_info(*db, study_id), {job}).at("jobs").at(0);
        out["study"] = study_id;
        return send_json(res, 200, out);
      }
    send_error(res, 404, "no job " + prefix + " in this store");
  });
}

}  // namespace railvsi::scheduler

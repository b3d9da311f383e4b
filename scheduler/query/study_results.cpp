#include "query/study_results.hpp"

#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

namespace railvsi::scheduler {
namespace {

// The filters are bound parameters; a NULL parameter disables its filter.
constexpr const char* kFilter =
    "sj.study_id = ?1 AND (?2 IS NULL OR j.train = ?2) AND (?3 IS NULL OR j.speed_kmh >= ?3) "
    "AND (?4 IS NULL OR j.speed_kmh <= ?4) AND (?5 IS NULL OR j.irregularity = ?5)";

void bind_filter(Statement& s, const QueryFilter& f) {
  s.bind(1, f.study_id);
  if (f.train) s.bind(2, *f.train); else s.bind_null(2);
  if (f.speed_min_kmh) s.bind(3, *f.speed_min_kmh); else s.bind_null(3);
  if (f.speed_max_kmh) s.bind(4, *f.speed_max_kmh); else s.bind_null(4);
  if (f.irregularity) s.bind(5, *f.irregularity); else s.bind_null(5);
}

}  // namespace

std::optional<double> JobResult::overall(const std::string& quantity) const {
  const auto q = envelopes.find(quantity);
  if (q == envelopes.end()) return std::nullopt;
  const auto v = q->second.find("");
  return v == q->second.end() ? std::nullopt : v->second;
}

StudyInfo study_info(Database& db, const std::string& study_id) {
  Statement s = db.prepare("SELECT id, name, file, checks, job_count FROM studies WHERE id = ?");
  if (!s.bind(1, study_id).step()) throw std::runtime_error(fmt::format("no study {} in {}", study_id, db.file()));
  return {s.text(0), s.text(1), s.text(2), nlohmann::json::parse(s.text(3)), s.int64(4)};
}

std::vector<JobResult> study_results(Database& db, const QueryFilter& filter) {
  std::vector<JobResult> jobs;
  std::unordered_map<std::string, std::size_t> index;
  Statement s = db.prepare(fmt::format(
      "SELECT j.id, j.train, j.speed_kmh, j.irregularity, j.state, j.status, j.error, j.dt_s, j.dt_reason, "
      "j.cutoff_hz, j.wall_s, j.loop_s, j.fidelity, j.warnings FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
      "WHERE {} ORDER BY sj.position",
      kFilter));
  bind_filter(s, filter);
  while (s.step()) {
    JobResult r;
    r.id = s.text(0);
    r.train = s.text(1);
    r.speed_kmh = s.real(2);
    r.irregularity = s.text(3);
    r.state = s.text(4);
    r.status = s.text(5);
    r.error = s.text(6);
    r.dt_s = s.real(7);
    r.dt_reason = s.text(8);
    r.cutoff_hz = s.real(9);
    r.wall_s = s.optional_real(10);
    r.loop_s = s.optional_real(11);
    r.fidelity = s.text(12);
    r.warnings = s.text(13);
    index.emplace(r.id, jobs.size());
    jobs.push_back(std::move(r));
  }
  Statement e = db.prepare(fmt::format(
      "SELECT e.job_id, e.quantity, e.location, e.value FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
      "JOIN envelopes e ON e.job_id = j.id WHERE {}",
      kFilter));
  bind_filter(e, filter);
  while (e.step()) {
    const auto it = index.find(e.text(0));
    if (it == index.end()) continue;
    jobs[it->second].envelopes[e.text(1)][e.text(2)] = e.optional_real(3);
  }
  return jobs;
}

}  // namespace railvsi::scheduler

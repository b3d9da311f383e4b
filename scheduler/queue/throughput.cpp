#include "queue/throughput.hpp"

#include <algorithm>

namespace railvsi::scheduler {
namespace {

// The jobs of one study, or all jobs.
std::string jobs_of(const std::string& study_id) {
  return study_id.empty() ? "jobs j WHERE 1"
                          : "study_job_links sj JOIN jobs j ON j.seq = sj.job_seq WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?1)";
}

}  // namespace

Throughput recent_throughput(Database& db, const std::string& study_id, const StateCounts& counts, double now_s) {
  Throughput t;
  Statement last = db.prepare("SELECT count(*), max(j.finished_at) FROM " + jobs_of(study_id) +
                              " AND j.state IN ('done', 'failed') AND j.finished_at IS NOT NULL");
  if (!study_id.empty()) last.bind(1, study_id);
  last.step();
  if (last.int64(0) == 0) return t;
  // While jobs are left the window runs to now, so a stall lowers the rate.
  const double end = counts.unfinished() > 0 ? now_s : last.real(1);
  Statement w = db.prepare("SELECT count(*), min(j.started_at) FROM " + jobs_of(study_id) +
                           " AND j.state IN ('done', 'failed') AND j.finished_at > ?2 AND j.finished_at <= ?3");
  if (!study_id.empty()) w.bind(1, study_id);
  w.bind(2, end - kThroughputWindow_s).bind(3, end).step();
  const std::int64_t recent = w.int64(0);
  const double begin = w.is_null(1) ? end - kThroughputWindow_s : std::max(end - kThroughputWindow_s, w.real(1));
  t.jobs_per_s = static_cast<double>(recent) / std::max(end - begin, 1e-3);
  if (*t.jobs_per_s > 0.0) t.eta_s = static_cast<double>(counts.unfinished()) / *t.jobs_per_s;
  return t;
}

}  // namespace railvsi::scheduler

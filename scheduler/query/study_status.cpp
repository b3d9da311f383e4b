#include "query/study_status.hpp"

#include <algorithm>

#include "core/unix_time.hpp"

namespace railvsi::scheduler {

StudyStatus study_status(Database& db, const std::string& study_id) {
  StudyStatus st;
  st.id = study_id;
  {
    Statement s = db.prepare("SELECT name FROM studies WHERE id = ?");
    if (s.bind(1, study_id).step()) st.name = s.text(0);
  }
  st.counts = state_counts(db, study_id);
  const double now = unix_now_s();
  {
    Statement s = db.prepare(
        "SELECT count(*) FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
        "WHERE sj.study_id = ? AND j.state = 'running' AND (j.lease_expires IS NULL OR j.lease_expires < ?)");
    s.bind(1, study_id).bind(2, now).step();
    st.stale_leases = s.int64(0);
  }
  {
    Statement s = db.prepare(
        "SELECT count(*), total(j.wall_s), total(j.loop_s), max(j.finished_at) "
        "FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
        "WHERE sj.study_id = ? AND j.state IN ('done', 'failed') AND j.finished_at IS NOT NULL");
    s.bind(1, study_id).step();
    const std::int64_t finished = s.int64(0);
    st.job_wall_s = s.real(1);
    st.loop_s = s.real(2);
    if (finished > 0) {
      // While jobs are left the window runs to now, so a stall lowers the rate.
      const double end = st.counts.unfinished() > 0 ? now : s.real(3);
      Statement w = db.prepare(
          "SELECT count(*), min(j.started_at) FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
          "WHERE sj.study_id = ? AND j.state IN ('done', 'failed') AND j.finished_at > ? AND j.finished_at <= ?");
      w.bind(1, study_id).bind(2, end - kThroughputWindow_s).bind(3, end).step();
      const std::int64_t recent = w.int64(0);
      const double begin = w.is_null(1) ? end - kThroughputWindow_s : std::max(end - kThroughputWindow_s, w.real(1));
      st.jobs_per_s = static_cast<double>(recent) / std::max(end - begin, 1e-3);
      if (*st.jobs_per_s > 0.0) st.eta_s = static_cast<double>(st.counts.unfinished()) / *st.jobs_per_s;
    }
  }
  {
    Statement s = db.prepare("SELECT factorizations, hits, factorization_s, evictions FROM cache_stats WHERE study_id = ?");
    if (s.bind(1, study_id).step()) {
      st.factorizations = s.int64(0);
      st.cache_hits = s.int64(1);
      st.factorization_s = s.real(2);
      st.evictions = s.int64(3);
    }
  }
  return st;
}

}  // namespace railvsi::scheduler

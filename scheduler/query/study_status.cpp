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
  {
    Statement s = db.prepare(
        "SELECT count(*), min(j.started_at), max(j.finished_at), total(j.wall_s), total(j.loop_s) "
        "FROM study_jobs sj JOIN jobs j ON j.id = sj.job_id "
        "WHERE sj.study_id = ? AND j.state IN ('done', 'failed') AND j.finished_at IS NOT NULL");
    s.bind(1, study_id).step();
    const std::int64_t finished = s.int64(0);
    st.job_wall_s = s.real(3);
    st.loop_s = s.real(4);
    if (finished > 0 && !s.is_null(1)) {
      // While jobs are still running the rate runs to now.
      const double end = st.counts.unfinished() > 0 ? unix_now_s() : s.real(2);
      const double span = std::max(end - s.real(1), 1e-3);
      st.jobs_per_s = static_cast<double>(finished) / span;
      st.eta_s = static_cast<double>(st.counts.unfinished()) / *st.jobs_per_s;
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

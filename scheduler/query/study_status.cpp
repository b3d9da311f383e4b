#include "query/study_status.hpp"

#include "core/unix_time.hpp"

namespace railvsi::scheduler {

StudyStatus study_status(Database& db, const std::string& study_id) { return study_status(db, study_id, unix_now_s()); }

StudyStatus study_status(Database& db, const std::string& study_id, double now) {
  StudyStatus st;
  st.id = study_id;
  {
    Statement s = db.prepare("SELECT name FROM studies WHERE id = ?");
    if (s.bind(1, study_id).step()) st.name = s.text(0);
  }
  st.counts = state_counts(db, study_id);
  {
    Statement s = db.prepare(
        "SELECT count(*) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
        "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) AND j.state = 'running' AND (j.lease_expires IS NULL OR j.lease_expires < ?)");
    s.bind(1, study_id).bind(2, now).step();
    st.stale_leases = s.int64(0);
  }
  {
    Statement s = db.prepare(
        "SELECT total(j.wall_s), total(j.loop_s) FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
        "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) AND j.state IN ('done', 'failed') AND j.finished_at IS NOT NULL");
    s.bind(1, study_id).step();
    st.job_wall_s = s.real(0);
    st.loop_s = s.real(1);
  }
  const Throughput throughput = recent_throughput(db, study_id, st.counts, now);
  st.jobs_per_s = throughput.jobs_per_s;
  st.eta_s = throughput.eta_s;
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

#include "query/bridge_results.hpp"

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "compliance/stored_checks.hpp"
#include "store/store_check.hpp"
#include "study/structure_variants.hpp"

namespace railvsi::scheduler {
namespace {

// The quantities the checks of a report judge (compliance_data): the
// stored checks' and, at the output points, the deflection and bending
// moment of the dynamic enhancement and the deck twist.
std::set<std::string> judged_quantities() {
  std::set<std::string> q{"deck_displacement_m", "bending_moment_Nm", "deck_twist_mm_per_3m"};
  for (const StoredCheckRule& rule : stored_check_rules()) q.insert(rule.quantity);
  return q;
}

struct EnvelopeKey {
  std::string quantity, location;
  bool read = false;
};

}  // namespace

struct BridgeReader::Statements {
  Statements(Database& database, const std::string& study, BridgeFields f)
      : fields(f),
        // Every (bridge, job) row of the study in the order of study_results:
        // the bridge's place, then the job's. Only numbers are sorted.
        rows(database.prepare("SELECT ss.name, j.rowid FROM study_bridge_jobs sb "
                        "JOIN study_bridges ss ON ss.study_seq = sb.study_seq AND ss.position = sb.position "
                        "JOIN study_job_links sj ON sj.study_seq = sb.study_seq AND sj.job_seq = sb.job_seq "
                        "JOIN jobs j ON j.seq = sb.job_seq WHERE sb.study_seq = (SELECT seq FROM studies WHERE id = ?) "
                        "ORDER BY sb.position, sj.position")),
        job(database.prepare(f == BridgeFields::kAll
                           ? fmt::format("SELECT {}, j.seq FROM jobs j LEFT JOIN scene_parts p ON p.part = j.scene_part "
                                         "LEFT JOIN step_reasons r ON r.number = j.step_reason "
                                         "LEFT JOIN fidelity_records f ON f.number = j.fidelity_record WHERE j.rowid = ?",
                                         job_result_columns("p.head || j.scene_speed || p.tail", "r.text", "f.record"))
                           : std::string("SELECT j.id, j.train, j.speed_kmh, j.irregularity, j.state, j.status, "
                                         "j.error, j.dt_s, j.cutoff_hz, j.seq, j.operator_key "
                                         "FROM jobs j WHERE j.rowid = ?"))),
        scene(database.prepare("SELECT json_extract(scene, '$.structure.variant'), json_type(scene, '$.train'), "
                         "json_extract(scene, '$.train') FROM job_scenes WHERE job_id = ?")),
        values(database.prepare("SELECT key, value, error_estimate FROM envelope_values WHERE job_seq = ?")),
        db(database),
        study_id(study) {
    rows.bind(1, study_id);
    const std::set<std::string> judged = judged_quantities();
    Statement k = db.prepare("SELECT key, quantity, location FROM envelope_keys");
    while (k.step()) {
      const std::int64_t key = k.int64(0);
      if (key < 0 || key > 1'000'000) continue;  // not one a completion writes
      if (keys.size() <= static_cast<std::size_t>(key)) keys.resize(static_cast<std::size_t>(key) + 1);
      keys[static_cast<std::size_t>(key)] = {k.text(1), k.text(2), f == BridgeFields::kAll || judged.count(k.text(1))};
    }
    pending = rows.step();
  }

  JobResult read_job(std::int64_t rowid) {
    job.reset();
    job.bind(1, rowid);
    if (!job.step()) throw std::runtime_error(fmt::format("job row {} vanished while the study was read", rowid));
    JobResult r;
    std::optional<std::int64_t> seq;
    if (fields == BridgeFields::kAll) {
      r = read_job_result(job, train_kinds);
      if (!job.is_null(kJobResultColumns)) seq = job.int64(kJobResultColumns);
    } else {
      r.id = job.text(0);
      r.train = job.text(1);
      r.speed_kmh = job.real(2);
      r.irregularity = job.text(3);
      r.state = job.text(4);
      r.status = job.text(5);
      r.error = job.text(6);
      r.dt_s = job.real(7);
      r.cutoff_hz = job.real(8);
      r.ran_dt_s = r.dt_s;
      if (!job.is_null(9)) seq = job.int64(9);
      // Jobs with one operator key share the structure model (a bound of it
      // scales its mass or stiffness, so it has its own key) and whether
      // the train is axle forces (the rail flexibility is in the key; the
      // modal rung runs axle forces only): one scene says both.
      const auto [it, fresh] = facts.try_emplace({r.train, job.text(10)});
      if (fresh) {
        it->second.first = "nominal";
        scene.reset();
        if (scene.bind(1, r.id).step()) {
          if (!scene.is_null(0)) it->second.first = variant_label(nlohmann::json::parse(scene.text(0)));
          it->second.second = train_kinds(scene.text(1), scene.text(2));
        } else {
          it->second.second = train_kinds("", "");
        }
      }
      r.variant = it->second.first;
      r.axle_forces = it->second.second;
    }
    if (seq && fields != BridgeFields::kLabels) {
      values.reset();
      values.bind(1, *seq);
      bool any = false;
      while (values.step()) {
        any = true;
        const std::int64_t key = values.int64(0);
        if (key < 0 || static_cast<std::size_t>(key) >= keys.size() || !keys[static_cast<std::size_t>(key)].read)
          continue;
        const EnvelopeKey& k = keys[static_cast<std::size_t>(key)];
        r.envelopes[k.quantity][k.location] = values.optional_real(1);
        if (const auto estimate = values.optional_real(2)) r.error_estimates[k.quantity][k.location] = *estimate;
      }
      if (!any && r.state == "done") bare_done_jobs.insert(rowid);
    } else if (fields != BridgeFields::kLabels && r.state == "done") {
      bare_done_jobs.insert(rowid);  // no number: no envelopes
    }
    return r;
  }

  BridgeFields fields;
  Statement rows, job, scene, values;
  std::vector<EnvelopeKey> keys;  // by envelope_keys.key
  TrainKinds train_kinds;
  // (train, operator key) -> (bound of the structure, axle forces)
  std::map<std::pair<std::string, std::string>, std::pair<std::string, std::optional<bool>>> facts;
  bool pending = false;  // rows holds the first row of the next bridge
  // Done jobs read without any envelope value (a damaged page reads as
  // fewer rows), by row (a job of two bridges is one): the study check
  // these reads stand for (StudyCheck::kLinks).
  std::set<std::int64_t> bare_done_jobs;
  Database& db;
  std::string study_id;
};

BridgeReader::BridgeReader(Database& db, const std::string& study_id, BridgeFields fields)
    : s_(std::make_unique<Statements>(db, study_id, fields)) {}

BridgeReader::~BridgeReader() = default;

bool BridgeReader::next(std::string& name, std::vector<JobResult>& jobs) {
  jobs.clear();
  if (!s_->pending) {
    // What require_consistent_study's kAll would have refused, found by reading.
    if (!s_->bare_done_jobs.empty())
      throw done_jobs_without_envelopes(s_->db, s_->study_id, static_cast<std::int64_t>(s_->bare_done_jobs.size()));
    return false;
  }
  name = s_->rows.text(0);
  // The facts of one scene per train and key hold within a bridge's jobs.
  s_->facts.clear();
  do {
    JobResult r = s_->read_job(s_->rows.int64(1));
    r.structure = name;
    jobs.push_back(std::move(r));
    s_->pending = s_->rows.step();
  } while (s_->pending && s_->rows.text(0) == name);
  return true;
}

}  // namespace railvsi::scheduler

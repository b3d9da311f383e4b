#include "query/study_results.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"
#include "study/structure_variants.hpp"

namespace railvsi::scheduler {
namespace {

// The filters are bound parameters; a NULL parameter disables its filter.
constexpr const char* kFilter =
    "sj.study_seq = (SELECT seq FROM studies WHERE id = ?1) AND (?2 IS NULL OR j.train = ?2) AND (?3 IS NULL OR j.speed_kmh >= ?3) "
    "AND (?4 IS NULL OR j.speed_kmh <= ?4) AND (?5 IS NULL OR j.irregularity = ?5) "
    "AND (?6 IS NULL OR ss.name = ?6)";

// The bridge of each row of a line study (none in a study of one structure),
// by the store's numbers (the view study_structures gives them by ids).
constexpr const char* kStructureJoin =
    "LEFT JOIN study_bridge_jobs sb ON sb.study_seq = sj.study_seq AND sb.job_seq = sj.job_seq "
    "LEFT JOIN study_bridges ss ON ss.study_seq = sb.study_seq AND ss.position = sb.position";

void bind_filter(Statement& s, const QueryFilter& f) {
  s.bind(1, f.study_id);
  if (f.train) s.bind(2, *f.train); else s.bind_null(2);
  if (f.speed_min_kmh) s.bind(3, *f.speed_min_kmh); else s.bind_null(3);
  if (f.speed_max_kmh) s.bind(4, *f.speed_max_kmh); else s.bind_null(4);
  if (f.irregularity) s.bind(5, *f.irregularity); else s.bind_null(5);
  if (f.structure) s.bind(6, *f.structure); else s.bind_null(6);
}

}  // namespace

std::optional<bool> TrainKinds::operator()(const std::string& type, const std::string& text) {
  const auto [it, fresh] = known_.try_emplace(type + ":" + text);
  if (fresh) {
    try {
      const nlohmann::json train = type == "text" ? nlohmann::json(text) : nlohmann::json::parse(text);
      it->second = parse_train_reference(train).is_moving_forces();
    } catch (const std::exception&) {  // a library train no longer there: not known
      it->second = std::nullopt;
    }
  }
  return it->second;
}

std::string job_result_columns(std::string_view scene, std::string_view dt_reason, std::string_view fidelity) {
  return fmt::format(
      "j.id, j.train, j.speed_kmh, j.irregularity, j.state, j.status, j.error, j.dt_s, {2}, "
      "j.cutoff_hz, j.wall_s, j.loop_s, {1}, j.warnings, "
      "CASE WHEN json_extract({0}, '$.irregularity.seed') IS NOT NULL "
      "THEN json_remove(json_extract({0}, '$.irregularity'), '$.seed') END, "
      "json_extract({0}, '$.irregularity.spectrum'), json_extract({0}, '$.structure.variant'), "
      "json_extract({1}, '$.dt_s'), json_type({0}, '$.train'), json_extract({0}, '$.train')",
      scene, fidelity, dt_reason);
}

JobResult read_job_result(Statement& s, TrainKinds& axle_forces) {
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
  r.profile_family = s.text(14);
  if (!r.profile_family.empty()) r.family_label = s.text(15);
  if (!s.is_null(16)) r.variant = variant_label(nlohmann::json::parse(s.text(16)));
  r.ran_dt_s = s.optional_real(17).value_or(r.dt_s);
  r.axle_forces = axle_forces(s.text(18), s.text(19));
  return r;
}

std::optional<double> JobResult::value(const std::string& quantity, const std::string& location) const {
  const auto q = envelopes.find(quantity);
  if (q == envelopes.end()) return std::nullopt;
  const auto v = q->second.find(location);
  return v == q->second.end() ? std::nullopt : v->second;
}

std::optional<double> JobResult::overall(const std::string& quantity) const { return value(quantity, ""); }

std::optional<double> JobResult::error_estimate(const std::string& quantity, const std::string& location) const {
  const auto q = error_estimates.find(quantity);
  if (q == error_estimates.end()) return std::nullopt;
  const auto v = q->second.find(location);
  return v == q->second.end() ? std::nullopt : std::optional(v->second);
}

std::vector<JobResult> jobs_with_vehicles(const std::vector<JobResult>& jobs) {
  std::vector<JobResult> out;
  for (const JobResult& j : jobs)
    if (!j.axle_forces.value_or(false)) out.push_back(j);
  return out;
}

StudyInfo study_info(Database& db, const std::string& study_id) {
  Statement s = db.prepare("SELECT id, name, file, checks, job_count, "
                           "coalesce(json_extract(document, '$.accuracy.tolerance'), 0.01) FROM studies WHERE id = ?");
  if (!s.bind(1, study_id).step()) throw std::runtime_error(fmt::format("no study {} in {}", study_id, db.file()));
  return {s.text(0), s.text(1), s.text(2), nlohmann::json::parse(s.text(3)), s.int64(4), s.real(5)};
}

std::vector<std::string> study_structure_names(Database& db, const std::string& study_id) {
  // The bridges that have jobs in this store (a shard holds some).
  Statement s = db.prepare("SELECT b.name FROM study_bridges b WHERE b.study_seq = (SELECT seq FROM studies WHERE id = ?1) "
                           "AND b.position IN (SELECT position FROM study_bridge_jobs WHERE study_seq = b.study_seq) "
                           "GROUP BY b.name ORDER BY min(b.position)");
  s.bind(1, study_id);
  std::vector<std::string> names;
  while (s.step()) names.push_back(s.text(0));
  return names;
}

std::vector<JobResult> study_results(Database& db, const QueryFilter& filter) {
  std::vector<JobResult> jobs;
  std::unordered_map<std::string, std::vector<std::size_t>> index;  // a job on two bridges is two rows
  TrainKinds axle_forces;
  Statement s = db.prepare(fmt::format("SELECT {}, ss.name FROM study_job_links sj {} JOIN job_records j ON j.seq = sj.job_seq "
                                       "WHERE {} ORDER BY coalesce(sb.position, 0), sj.position",
                                       job_result_columns("j.scene", "j.dt_reason", "j.fidelity"), kStructureJoin, kFilter));
  bind_filter(s, filter);
  while (s.step()) {
    JobResult r = read_job_result(s, axle_forces);
    r.structure = s.text(kJobResultColumns);
    index[r.id].push_back(jobs.size());
    jobs.push_back(std::move(r));
  }
  Statement e = db.prepare(fmt::format(
      "SELECT DISTINCT j.id, e.quantity, e.location, e.value, e.error_estimate FROM study_job_links sj {} "
      "JOIN jobs j ON j.seq = sj.job_seq JOIN job_envelopes e ON e.job_seq = j.seq WHERE {}",
      kStructureJoin, kFilter));
  bind_filter(e, filter);
  while (e.step()) {
    const auto it = index.find(e.text(0));
    if (it == index.end()) continue;
    for (std::size_t k : it->second) {
      jobs[k].envelopes[e.text(1)][e.text(2)] = e.optional_real(3);
      if (const auto estimate = e.optional_real(4)) jobs[k].error_estimates[e.text(1)][e.text(2)] = *estimate;
    }
  }
  return jobs;
}

namespace {

// Distinct labels of one column of a study's jobs, in study order. `column`
// is one of ours (train, irregularity), never user text.
std::vector<std::string> study_labels(Database& db, const std::string& study_id, std::string_view column) {
  Statement s = db.prepare(fmt::format("SELECT j.{0} FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq "
                                       "WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?) GROUP BY j.{0} ORDER BY min(sj.position)",
                                       column));
  s.bind(1, study_id);
  std::vector<std::string> labels;
  while (s.step()) labels.push_back(s.text(0));
  return labels;
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::optional<std::string> unknown_label(Database& db, const std::string& study_id, std::string_view column,
                                         std::string_view option, const std::string& value) {
  const std::vector<std::string> known = study_labels(db, study_id, column);
  if (std::find(known.begin(), known.end(), value) != known.end()) return std::nullopt;
  std::string hint;
  for (const std::string& k : known)
    if (lower(k) == lower(value)) hint = fmt::format(" (names are case-sensitive: '{}')", k);
  std::string list;
  for (const std::string& k : known) list += fmt::format("{}'{}'", list.empty() ? "" : ", ", k);
  return fmt::format("{} '{}': the study {} has no such {}{}; it has: {}", option, value, study_id.substr(0, 12),
                     column == "train" ? "train" : "irregularity profile", hint, list);
}

}  // namespace

std::optional<std::string> filter_error(Database& db, const QueryFilter& f) {
  if (f.speed_min_kmh && f.speed_max_kmh && *f.speed_min_kmh > *f.speed_max_kmh)
    return fmt::format("--speed-min {} is above --speed-max {}: no speed can match", *f.speed_min_kmh,
                       *f.speed_max_kmh);
  if (f.train)
    if (auto why = unknown_label(db, f.study_id, "train", "--train", *f.train)) return why;
  if (f.irregularity)
    if (auto why = unknown_label(db, f.study_id, "irregularity", "--irregularity", *f.irregularity)) return why;
  if (f.structure) {
    const std::vector<std::string> known = study_structure_names(db, f.study_id);
    if (known.empty())
      return fmt::format("--structure '{}': the study {} has one structure (no \"structures\")", *f.structure,
                         f.study_id.substr(0, 12));
    if (std::find(known.begin(), known.end(), *f.structure) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += fmt::format("{}'{}'", list.empty() ? "" : ", ", k);
      return fmt::format("--structure '{}': the study {} has no such structure; it has: {}", *f.structure,
                         f.study_id.substr(0, 12), list);
    }
  }
  if (f.speed_min_kmh || f.speed_max_kmh) {
    // A range that holds none of the study's speeds, outside them or between
    // two of them, matches nothing.
    Statement s = db.prepare(
        "SELECT min(j.speed_kmh), max(j.speed_kmh), "
        "sum((?2 IS NULL OR j.speed_kmh >= ?2) AND (?3 IS NULL OR j.speed_kmh <= ?3)), "
        "max(CASE WHEN j.speed_kmh < ?2 THEN j.speed_kmh END), min(CASE WHEN j.speed_kmh > ?3 THEN j.speed_kmh END) "
        "FROM study_job_links sj JOIN jobs j ON j.seq = sj.job_seq WHERE sj.study_seq = (SELECT seq FROM studies WHERE id = ?1)");
    s.bind(1, f.study_id);
    if (f.speed_min_kmh) s.bind(2, *f.speed_min_kmh); else s.bind_null(2);
    if (f.speed_max_kmh) s.bind(3, *f.speed_max_kmh); else s.bind_null(3);
    s.step();
    if (!s.is_null(0) && s.int64(2) == 0) {
      const std::string range =
          fmt::format("the speed range [{}, {}] km/h holds no speed of the study",
                      f.speed_min_kmh ? fmt::format("{}", *f.speed_min_kmh) : std::string("-"),
                      f.speed_max_kmh ? fmt::format("{}", *f.speed_max_kmh) : std::string("-"));
      if (!s.is_null(3) && !s.is_null(4))
        return fmt::format("{}: it lies between two of its speeds, {} and {} km/h", range, s.real(3), s.real(4));
      return fmt::format("{}, whose speeds run from {} to {} km/h", range, s.real(0), s.real(1));
    }
  }
  return std::nullopt;
}

Scene load_job_scene(Database& db, const std::string& job_id) {
  Statement s = db.prepare("SELECT scene FROM job_scenes WHERE job_id = ?");
  if (!s.bind(1, job_id).step()) throw std::runtime_error("job " + job_id + " is not in the database");
  const std::string name = "job " + job_id.substr(0, 12);
  return parse_scene(parse_json_text(s.text(0), name), "/", name);
}

}  // namespace railvsi::scheduler

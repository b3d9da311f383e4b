#include "query/stored_statics.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "query/bridge_results.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi::scheduler {
namespace {

constexpr const char* kDeflection = "deck_displacement_m";
constexpr const char* kMoment = "bending_moment_Nm";
constexpr const char* kShear = "shear_force_N";
constexpr const char* kReaction = "support_reaction_N";
constexpr const char* kRotation = "support_rotation_rad";

// SQLite keeps a REAL's bits except a negative zero's (read back as +0) and
// a NaN's (NULL): such an envelope is not stored, and is computed again.
bool storable(double v) { return !std::isnan(v) && !(v == 0.0 && std::signbit(v)); }

struct Row {
  const char* quantity;
  int place;
  std::string location;
  std::optional<double> value;
};

// Every value of `s` as the rows that hold it; empty when one is not storable.
std::vector<Row> rows_of(const StaticInfluence& influence, const TrainStatics& s) {
  std::vector<Row> rows;
  const auto& points = influence.structure().outputs();
  const auto& supports = influence.section_forms().supports;
  if (s.max_deflection_m.size() != points.size()) return {};
  for (std::size_t k = 0; k < points.size(); ++k)
    rows.push_back({kDeflection, static_cast<int>(k), points[k].name, s.max_deflection_m[k]});
  if (s.sections.unavailable.empty()) {
    if (s.sections.max_abs_bending_moment_Nm.size() != points.size() ||
        s.sections.max_abs_shear_force_N.size() != points.size() || s.sections.max_reaction_N.size() != supports.size() ||
        s.sections.max_abs_rotation_rad.size() != supports.size())
      return {};
    for (std::size_t k = 0; k < points.size(); ++k) {
      rows.push_back({kMoment, static_cast<int>(k), points[k].name, s.sections.max_abs_bending_moment_Nm[k]});
      rows.push_back({kShear, static_cast<int>(k), points[k].name, s.sections.max_abs_shear_force_N[k]});
    }
    for (std::size_t i = 0; i < supports.size(); ++i) {
      rows.push_back({kReaction, static_cast<int>(i), supports[i].name, s.sections.max_reaction_N[i]});
      rows.push_back({kRotation, static_cast<int>(i), supports[i].name, s.sections.max_abs_rotation_rad[i]});
    }
  }
  for (const Row& r : rows)
    if (r.value && !storable(*r.value)) return {};
  return rows;
}

}  // namespace

StaticSceneJobs static_scene_jobs(const std::vector<JobResult>& jobs) {
  StaticSceneJobs out;
  std::map<std::string, bool> nominal;  // train -> its job found is of the nominal structure
  for (const JobResult& j : jobs) {
    const auto [it, fresh] = nominal.try_emplace(j.train, j.variant == "nominal");
    if (fresh) out.train_job[j.train] = j.id;
    else if (!it->second && j.variant == "nominal") it->second = true, out.train_job[j.train] = j.id;
  }
  if (!out.train_job.empty()) out.structure_job = out.train_job.begin()->second;
  return out;
}

TrainStatics compute_train_statics(const StaticInfluence& influence, const std::vector<MovingForce>& axles) {
  TrainStatics s;
  s.sections = influence.section_envelope(axles);
  for (std::size_t k = 0; k < influence.structure().outputs().size(); ++k)
    s.max_deflection_m.push_back(influence.train_envelope(static_cast<int>(k), axles).max_deflection_m);
  return s;
}

std::optional<TrainStatics> read_train_statics(Database& db, const std::string& structure_job,
                                               const std::string& train_job, const StaticInfluence& influence) {
  const std::size_t n = influence.structure().outputs().size();
  const SectionForms& forms = influence.section_forms();
  const std::size_t supports = forms.supports.size();
  TrainStatics s;
  s.max_deflection_m.assign(n, 0.0);
  if (!forms.available()) {
    s.sections.unavailable = forms.unavailable;
  } else {
    s.sections.max_abs_bending_moment_Nm.resize(n);
    s.sections.max_abs_shear_force_N.resize(n);
    s.sections.max_reaction_N.assign(supports, 0.0);
    s.sections.max_abs_rotation_rad.assign(supports, 0.0);
  }
  const std::size_t expected = n + (forms.available() ? 2 * n + 2 * supports : 0);
  std::size_t found = 0;
  Statement q = db.prepare("SELECT quantity, place, value FROM static_envelopes WHERE structure_job = ? AND train_job = ?");
  q.bind(1, structure_job).bind(2, train_job);
  while (q.step()) {
    const std::string quantity = q.text(0);
    const std::int64_t place = q.int64(1);
    const std::optional<double> v = q.optional_real(2);
    if (place < 0) return std::nullopt;
    const auto p = static_cast<std::size_t>(place);
    const bool section = quantity == kMoment || quantity == kShear;
    const bool support = quantity == kReaction || quantity == kRotation;
    if (quantity == kDeflection && p < n && v) s.max_deflection_m[p] = *v;
    else if (section && forms.available() && p < n)
      (quantity == kMoment ? s.sections.max_abs_bending_moment_Nm : s.sections.max_abs_shear_force_N)[p] = v;
    else if (support && forms.available() && p < supports && v)
      (quantity == kReaction ? s.sections.max_reaction_N : s.sections.max_abs_rotation_rad)[p] = *v;
    else
      return std::nullopt;  // a row of another structure's shape: not these envelopes
    ++found;
  }
  if (found != expected || expected == 0) return std::nullopt;
  return s;
}

void write_train_statics(Database& db, const std::string& structure_job, const std::string& train_job,
                         const StaticInfluence& influence, const TrainStatics& statics) {
  const std::vector<Row> rows = rows_of(influence, statics);
  Statement insert = db.prepare("INSERT OR IGNORE INTO static_envelopes (structure_job, train_job, quantity, place, "
                                "location, value) VALUES (?, ?, ?, ?, ?, ?)");
  for (const Row& r : rows) {
    insert.reset();
    insert.bind(1, structure_job).bind(2, train_job).bind(3, r.quantity).bind(4, r.place).bind(5, r.location);
    if (r.value) insert.bind(6, *r.value);
    else insert.bind_null(6);
    insert.run();
  }
}

std::size_t store_static_envelopes(Database& db, const std::string& study_id) {
  std::size_t computed = 0;
  // Bridge by bridge as the line table reads them (one bridge's job labels
  // in memory), each bridge's rows written in a short transaction of its own:
  // workers of the study may be completing jobs.
  BridgeReader reader(db, study_id, BridgeFields::kLabels);
  std::string name;
  std::vector<JobResult> jobs;
  while (reader.next(name, jobs)) {
    const StaticSceneJobs picked = static_scene_jobs(jobs);
    if (picked.structure_job.empty()) continue;
    const Scene structure_scene = load_job_scene(db, picked.structure_job);
    std::optional<StaticInfluence> influence;
    try {
      influence.emplace(*structure_scene.structure, structure_scene.analysis.contact.rail_lines);
    } catch (const std::exception&) {
      continue;  // the report says why, from its own attempt
    }
    std::vector<std::pair<std::string, TrainStatics>> fresh;
    for (const auto& [train, job] : picked.train_job) {
      if (read_train_statics(db, picked.structure_job, job, *influence)) continue;
      const std::vector<MovingForce> axles =
          axle_loads(job == picked.structure_job ? structure_scene.train : load_job_scene(db, job).train);
      fresh.emplace_back(job, compute_train_statics(*influence, axles));
      ++computed;
    }
    if (fresh.empty()) continue;
    Transaction tx(db);
    for (const auto& [job, statics] : fresh) write_train_statics(db, picked.structure_job, job, *influence, statics);
    tx.commit();
  }
  return computed;
}

std::size_t store_missing_static_envelopes(Database& db) {
  std::vector<std::string> studies;
  Statement s = db.prepare("SELECT DISTINCT study_id FROM study_structures ORDER BY study_id");
  while (s.step()) studies.push_back(s.text(0));
  std::size_t computed = 0;
  for (const std::string& id : studies) computed += store_static_envelopes(db, id);
  return computed;
}

}  // namespace railvsi::scheduler

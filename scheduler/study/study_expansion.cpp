#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/sha256.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "io/schema_validator.hpp"
#include "io/train_sets.hpp"
#include "simulation/simulation.hpp"
#include "solver/hybrid_operator.hpp"
#include "study/canonical_json.hpp"
#include "envelopes/code_filter.hpp"
#include "planning/time_step_policy.hpp"
#include "analysis/modal_moving_forces.hpp"
#include "planning/effects_planner.hpp"
#include "planning/deck_frequencies.hpp"
#include "planning/scene_plan.hpp"
#include "study/speed_list.hpp"
#include "study/structure_key.hpp"
#include "planning/time_step_warnings.hpp"
#include "study/structure_variants.hpp"
#include "study/study_structures.hpp"
#include "study/study_plan.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::json;

struct Profile {
  json value;  // null: perfect track
  std::string label;
  std::string path;  // where its errors are reported in the study
};

bool starts_path(const std::string& path, std::string_view prefix) {
  return path.starts_with(prefix) && (path.size() == prefix.size() || path[prefix.size()] == '/');
}

// An error found while building one scene of the study, placed in the study:
// /train -> /trains/<i>, /irregularity -> /irregularities/<j>, /speed_kmh ->
// /speeds_kmh, /structure (and /outputs of a bridge that has its own) -> the
// bridge (a CSV line names itself). Errors of another document (a library
// train) pass as they are.
InputError in_study(const InputError& e, const std::string& file, const std::string& train_path,
                    const std::string& profile_path, const NamedStructure& structure) {
  if (!e.file().empty() && e.file() != file) return e;
  const std::string& p = e.json_path();
  std::string mapped = p;
  std::string what = e.what();
  const bool own_outputs = !structure.outputs.is_null() && starts_path(p, "/outputs");
  if (starts_path(p, "/train")) mapped = train_path + p.substr(6);
  else if (starts_path(p, "/irregularity")) mapped = profile_path + p.substr(13);
  else if (starts_path(p, "/speed_kmh")) mapped = "/speeds_kmh" + p.substr(10);
  else if (!structure.name.empty() && (starts_path(p, "/structure") || own_outputs)) {
    if (!structure.origin.empty()) {
      mapped = structure.path;
      what = fmt::format("{}: bridge '{}': {}: {}", structure.origin, structure.name, p, what);
    } else {
      mapped = own_outputs ? structure.path.substr(0, structure.path.size() - 10) + p : structure.path + p.substr(10);
    }
  }
  return InputError(mapped, what, file);
}

}  // namespace

std::string study_train_label(const json& train) {
  if (train.is_string()) return train.get<std::string>();
  if (train.contains("library")) {
    const std::string name = train.at("library").get<std::string>();
    return train.contains("as") ? fmt::format("{} as {}", name, train.at("as").get<std::string>()) : name;
  }
  return train.at("name").get<std::string>();
}

namespace {

std::string profile_label(const json& p, std::size_t index) {
  if (p.is_null()) return "none";
  std::string label;
  if (p.contains("spectrum"))
    label = fmt::format("{} seed {}", p.at("spectrum").get<std::string>(), p.at("seed").dump());
  else if (p.contains("csv"))
    label = std::filesystem::path(p.at("csv").get<std::string>()).filename().string();
  else if (p.contains("x_m"))
    label = fmt::format("profile {}", index + 1);
  if (p.contains("defects")) label += label.empty() ? fmt::format("defects {}", index + 1) : " + defects";
  return label;
}

// Labels name rows of the result tables: make repeated ones unique.
void make_unique(std::vector<std::string>& labels) {
  std::map<std::string, int> seen;
  for (const auto& l : labels) ++seen[l];
  std::map<std::string, int> used;
  for (auto& l : labels)
    if (seen[l] > 1) l += fmt::format(" #{}", ++used[l]);
}

std::vector<Profile> study_profiles(const json& study) {
  std::vector<Profile> profiles;
  if (!study.contains("irregularities")) return {{json(nullptr), "none", "/irregularities"}};
  const json& list = study.at("irregularities");
  for (std::size_t j = 0; j < list.size(); ++j) {
    const json& item = list[j];
    const std::string path = child_path("/irregularities", j);
    if (item.is_object() && item.contains("seeds")) {
      if (!item.at("irregularity").contains("spectrum"))
        throw InputError(path + "/irregularity", "seeds need a spectrum profile (\"spectrum\" and \"seed\")");
      for (const json& seed : item.at("seeds")) {
        json p = item.at("irregularity");
        p["seed"] = seed;
        profiles.push_back({p, profile_label(p, j), path + "/irregularity"});
      }
    } else {
      profiles.push_back({item, profile_label(item, j), path});
    }
  }
  std::vector<std::string> labels;
  for (const auto& p : profiles) labels.push_back(p.label);
  make_unique(labels);
  for (std::size_t k = 0; k < profiles.size(); ++k) profiles[k].label = labels[k];
  return profiles;
}

// Jobs may run on another machine or from another directory: file names
// become absolute, resolved from the study's directory.
void make_absolute(json& node, const char* key, const std::filesystem::path& base_dir) {
  if (node.is_object() && node.contains(key) && node.at(key).is_string())
    node[key] = resolve_relative(base_dir, node.at(key).get<std::string>()).lexically_normal().string();
}

void absolute_file_names(std::vector<NamedStructure>& structures, std::vector<Profile>& profiles,
                         const std::filesystem::path& base_dir) {
  for (NamedStructure& s : structures)
    if (s.structure.contains("import"))
      for (const char* key : {"K", "M", "C", "map"}) make_absolute(s.structure["import"], key, base_dir);
  for (Profile& p : profiles) make_absolute(p.value, "csv", base_dir);
}

// What every job of one train on one variant of the structure shares: its
// structure (the train may size the approach embankment), whose hash and
// cut-off are computed once, and its speeds.
struct TrainFacts {
  std::string structure_hash;
  DeckFrequencies frequencies;
  double cutoff_hz = 0.0;
  bool rail_flexibility = false;
  std::shared_ptr<const StructureModel> structure;
  Scene first_scene;
  EffectsPlan plan;             // the rung of this train's jobs
  int modes = 0;                // the exact modal rung: the modes of its basis
  int hybrid_modes = 0;         // the hybrid rung: the bridge modes its dry run kept
  nlohmann::json fidelity;      // what the job scenes say of it (null: the study's own)
  std::vector<double> speeds_kmh;
};

// What the study asks of its jobs: its asks when given; else from its
// checks: the deck and the section forces always, wheel unloading and
// comfort when a check needs them; with no checks at all, what the train
// can give.
StudyAsks study_asks(const json& doc, bool load_model) {
  if (doc.contains("asks")) return asks_from_list(doc.at("asks").get<std::vector<std::string>>());
  StudyAsks a;
  if (!doc.contains("checks") || doc.at("checks").empty()) {
    a.wheel_unloading = a.comfort = !load_model;
    return a;
  }
  const json& c = doc.at("checks");
  a.wheel_unloading = c.contains("max_unloading_ratio");
  a.comfort = c.contains("carbody_acceleration_limit_mps2") || c.contains("comfort_level");
  return a;
}

struct JobTimeStep {
  double dt_s = 0.0;
  std::string reason;
};

// The study's dt_s, else on the modal rung the sampling step of the code
// frequency, else the policy's rung of the ladder for this train,
// structure and speed.
JobTimeStep job_time_step(bool dt_given, const Scene& scene, const DeckFrequencies& f, const EffectsPlan& plan) {
  if (dt_given) return {scene.analysis.dt_s, "given in the study (analysis.dt_s)"};
  if (plan.rung.exact_modal()) {
    const ModalPeaks peaks = modal_peaks_of(scene);
    const bool sampled = peaks == ModalPeaks::kSampled;
    const double dt = modal_time_step_s(plan.code_frequency_hz, scene.fidelity.tolerance, peaks);
    return {dt, fmt::format("modal rung (exact recurrence: dt samples the load and output only): the peak at the code "
                            "frequency {:.1f} Hz {} within the tolerance {:g} needs {:.3e} s",
                            plan.code_frequency_hz,
                            sampled ? "sampled (deck twist)"
                            : peaks == ModalPeaks::kRefinedWithSections ? "refined between samples (with section forces)"
                                                                        : "refined between samples",
                            scene.fidelity.tolerance, dt)};
  }
  TimeStepPolicy policy;
  policy.hht = scene.analysis.hht;
  const TimeStepChoice c = choose_time_step(*scene.structure, scene.train, scene.speed_mps, scene.analysis.contact,
                                            f.f0_hz, f.f3_hz, policy, scene.irregularity.get());
  return {c.dt_s, c.reason};
}

}  // namespace

StudyPlan expand_study(const json& given, const std::filesystem::path& study_dir, const std::string& file,
                       const ExpandOptions& options) {
  // Absolute from the start: a relative directory ("d3", or "" for a study
  // in the working directory) would leave names relative in the stored
  // scenes, and the check below would resolve them against it a second time.
  const std::filesystem::path base_dir =
      (study_dir.empty() ? std::filesystem::current_path() : std::filesystem::absolute(study_dir)).lexically_normal();
  shared_schema_validator("study.schema.json").validate(given, file);
  // "set:<name>" trains become the set's trains: the stored study, its jobs
  // and its reports see the trains themselves.
  json doc = given;
  std::vector<std::string> train_paths;  // each train's place in the given study
  doc["trains"] = expand_train_sets(given.at("trains"), file, &train_paths);
  // analysis may be left out: every option at its default.
  const json analysis = doc.contains("analysis") ? doc.at("analysis") : json::object();
  const bool dt_given = analysis.contains("dt_s");
  const std::size_t max_jobs = options.allow_large ? SIZE_MAX : options.max_jobs;

  StudyPlan plan;
  plan.file = file;
  plan.document = canonical_text(doc);
  plan.id = sha256_hex(plan.document);
  plan.name = doc.contains("name") ? doc.at("name").get<std::string>() : std::filesystem::path(file).filename().string();
  if (doc.contains("checks")) plan.checks = doc.at("checks");

  const json& trains = doc.at("trains");
  {
    // The same train twice ran the same jobs under two labels ("HSLM-A1 #1",
    // "#2"); trains that differ but share a name keep numbered labels.
    std::map<std::string, std::size_t> first_at;
    for (std::size_t j = 0; j < trains.size(); ++j)
      if (const auto [it, fresh] = first_at.try_emplace(canonical_text(trains[j]), j); !fresh)
        throw InputError(train_paths[j],
                         fmt::format("the same train as {}: list each train once ({})", train_paths[it->second],
                                     study_train_label(trains[j])),
                         file);
  }
  std::vector<double> speeds;  // given in speeds_kmh; a line_speed_kmh range adds per train and variant
  std::optional<LineSpeedRange> line_range;
  std::vector<StructureVariant> variants;
  std::vector<NamedStructure> structures = study_structures(doc, base_dir, file);
  if (structures.size() > 1 || !structures.front().name.empty())
    if (doc.value("refine", false))
      throw InputError("/refine", "speed refinement is not available for a line of structures yet: give the "
                                  "speeds finer, or refine a study of one bridge", file);
  try {
    if (doc.contains("speeds_kmh")) speeds = expand_speeds(doc.at("speeds_kmh"), max_jobs);
    line_range = line_speed_range(doc);
    if (speeds.empty() && !line_range)
      throw InputError("/speeds_kmh", "give the speeds (speeds_kmh), the maximum line speed (line_speed_kmh) or both");
    variants = study_variants(doc, max_jobs);
  } catch (const InputError& e) {
    throw e.with_file(file);
  }
  std::vector<Profile> profiles = study_profiles(doc);
  const auto check_count = [&](std::size_t count, std::size_t speed_count) {
    if (count > max_jobs)
      throw InputError(line_range ? "/line_speed_kmh" : "/speeds_kmh",
                       fmt::format("the study expands into {} jobs ({} structures x {} variants x {} trains x {} "
                                   "speeds x {} profiles), more than {}; pass --allow-large to submit it anyway",
                                   count, structures.size(), variants.size(), trains.size(), speed_count,
                                   profiles.size(), max_jobs),
                       file);
  };
  check_count(structures.size() * variants.size() * trains.size() * speeds.size() * profiles.size(), speeds.size());
  const double first_speed_kmh = speeds.empty() ? line_range->min_kmh : speeds.front();

  absolute_file_names(structures, profiles, base_dir);
  json base = json::object();
  base["analysis"] = analysis;
  if (doc.contains("outputs")) base["outputs"] = doc.at("outputs");
  if (doc.contains("accuracy")) {
    // "verify" is the study's (study_verification), not the run's: asking it
    // leaves the jobs, their ids and their envelopes as they are.
    base["accuracy"] = doc.at("accuracy");
    base["accuracy"].erase("verify");
    if (base["accuracy"].empty()) base.erase("accuracy");
  }
  if (doc.contains("asks")) base["asks"] = doc.at("asks");
  // Fidelity "auto" (the default): the planner pins each train's rung in its jobs.
  const bool auto_fidelity = !doc.contains("fidelity") || doc.at("fidelity").is_string();
  if (!auto_fidelity) base["fidelity"] = doc.at("fidelity");
  // A bridge of a line: the scene of a study of it alone.
  const auto scene_doc = [&](const NamedStructure& structure, const StructureVariant& variant, const json& train,
                             double speed_kmh, const json& profile, double dt_s) {
    json scene = base;
    scene["structure"] = structure.structure;
    if (!structure.outputs.is_null()) scene["outputs"] = structure.outputs;
    if (!variant.nominal()) scene["structure"]["variant"] = variant.scene_value();
    scene["train"] = train;
    scene["speed_kmh"] = speed_kmh;
    scene["irregularity"] = profile;
    scene["analysis"]["dt_s"] = dt_s;
    return scene;
  };
  ImportedStructures imports;  // a model's files read once for every train
  const auto parse = [&](const json& scene, const std::string& train_path, const std::string& profile_path,
                         const NamedStructure& structure) {
    try {
      return parse_scene(scene, base_dir, file, &imports);
    } catch (const InputError& e) {
      throw in_study(e, file, train_path, profile_path, structure);
    }
  };

  // Every train at the first speed over the first profile: the train, the
  // structure it runs on and the engine's setup (a dry run, without the
  // time loop). Then every other profile with the first train.
  const double placeholder_dt_s = dt_given ? analysis.at("dt_s").get<double>() : 1e-3;
  // Facts of train i on variant v of structure s at [(s * variants + v) * trains + i].
  std::vector<TrainFacts> facts(structures.size() * variants.size() * trains.size());
  std::map<std::string, DeckFrequencies> frequencies_of_structure;
  std::map<std::string, std::shared_ptr<const StructureOperator>> operators;
  std::map<std::string, int> modes_of_structure;
  std::map<std::pair<std::string, double>, std::shared_ptr<const ModalBasis>> bases;
  std::size_t count = 0, most_speeds = 0;
  for (std::size_t n = 0; n < facts.size(); ++n) {
    const std::size_t i = n % trains.size();
    const StructureVariant& variant = variants[(n / trains.size()) % variants.size()];
    const NamedStructure& structure = structures[n / (trains.size() * variants.size())];
    const std::string& train_path = train_paths[i];
    TrainFacts& f = facts[n];
    f.first_scene =
        parse(scene_doc(structure, variant, trains[i], first_speed_kmh, profiles.front().value, placeholder_dt_s),
              train_path, profiles.front().path, structure);
    f.structure = f.first_scene.structure;
    f.structure_hash = structure_model_hash(*f.structure);
    f.rail_flexibility = !f.first_scene.train.is_moving_forces();
    auto [it, fresh] = frequencies_of_structure.try_emplace(f.structure_hash);
    if (fresh) it->second = deck_frequencies(*f.structure);
    f.frequencies = it->second;
    f.first_scene.analysis.structure_f0_hz = f.frequencies.f0_hz;
    f.cutoff_hz = code_cutoff_hz(f.frequencies.f0_hz, f.frequencies.f3_hz);
    if (auto_fidelity) {
      const double modal_cutoff_hz = kModalCutoffMargin * f.cutoff_hz;
      // Counted once per structure, and only where the planner may choose a
      // modal rung: moving forces (interaction stays on FE,
      // kModalInteractionNotTrusted).
      int modes = -1;
      if (f.first_scene.train.is_moving_forces() && f.frequencies.f0_hz > 0.0 && f.frequencies.f3_hz > 0.0) {
        auto [m, fresh] = modes_of_structure.try_emplace(f.structure_hash, -1);
        if (fresh) m->second = count_modes(f.structure, modal_cutoff_hz, f.frequencies.lowest_hz);
        modes = m->second;
      }
      f.plan = plan_effects(planner_input(f.first_scene, study_asks(doc, f.first_scene.train.is_moving_forces()),
                                          f.frequencies, modes));
      f.fidelity = pinned_fidelity_json(f.plan);
    } else {
      const ScenePlan pinned = plan_scene(f.first_scene, f.frequencies);
      f.plan.rung = pinned.rung;
      f.plan.code_frequency_hz = f.cutoff_hz;
      f.plan.modal_cutoff_hz = pinned.modal_cutoff_hz;
    }
    f.speeds_kmh = speeds;
    if (line_range) {
      const std::optional<double> zeta = f.structure->info().damping_ratio;
      try {
        const std::vector<double> range =
            line_speed_speeds(*line_range, f.frequencies.f0_hz, f.first_scene.train.coach_length_m,
                              zeta ? *zeta : 0.0, max_jobs);
        f.speeds_kmh.insert(f.speeds_kmh.end(), range.begin(), range.end());
      } catch (const InputError& e) {
        throw e.with_file(file);
      }
      std::sort(f.speeds_kmh.begin(), f.speeds_kmh.end());
      f.speeds_kmh.erase(std::unique(f.speeds_kmh.begin(), f.speeds_kmh.end()), f.speeds_kmh.end());
    }
    count += f.speeds_kmh.size() * profiles.size();
    most_speeds = std::max(most_speeds, f.speeds_kmh.size());
    check_count(count, most_speeds);
    Scene dry = f.first_scene;
    // At the slowest speed: the longest run, which the size limits judge.
    if (!f.speeds_kmh.empty()) dry.speed_mps = *std::min_element(f.speeds_kmh.begin(), f.speeds_kmh.end()) / 3.6;
    const JobTimeStep first_dt = job_time_step(dt_given, dry, f.frequencies, f.plan);
    dry.analysis.dt_s = first_dt.dt_s;
    try {
      if (f.plan.rung.exact_modal()) {
        // The modal rung's setup: its modes and the train on its rails.
        // The modes once per structure and cut-off, as the workers share them.
        auto& basis = bases[{f.structure_hash, f.plan.modal_cutoff_hz}];
        if (!basis) {
          ModalBasisOptions mo;
          mo.max_frequency_hz = f.plan.modal_cutoff_hz;
          basis = std::make_shared<const ModalBasis>(f.structure, mo);
        }
        const ModalSweep sweep(*basis, dry.train, dry.analysis.contact.rail_lines, dry.analysis.dt_s);
        (void)modal_run_steps(dry);
        f.modes = basis->num_modes();
      } else {
        ScenePlan on_rung;
        on_rung.rung = f.plan.rung;
        on_rung.modal_cutoff_hz = f.plan.modal_cutoff_hz;
        apply_rung_structure(on_rung, dry.analysis);
        const std::string key = operator_key(f.structure_hash, dry.analysis, f.rail_flexibility);
        auto& op = operators[key];
        if (!op) op = options.operators ? options.operators(dry, key) : make_structure_operator(dry);
        if (const auto* hybrid = dynamic_cast<const HybridOperator*>(op.get()))
          f.hybrid_modes = hybrid->basis().num_modes();
        const Simulation setup(dry, op);
      }
    } catch (const InputError& e) {
      // A planned step too small to run comes from the study's tolerance.
      if (!dt_given && e.json_path() == "/analysis/dt_s" && doc.contains("accuracy") &&
          doc.at("accuracy").contains("tolerance") && doc.at("accuracy").at("tolerance").get<double>() < FidelityRequest{}.tolerance)
        throw InputError("/accuracy/tolerance",
                         fmt::format("{} (the step was planned from this tolerance)", e.what()), file);
      throw in_study(e.with_file(file), file, train_path, profiles.front().path, structure);
    }
  }
  // Each profile's irregularity, for the time-step policy's track bound
  // (its shortest feature does not depend on the range sampled).
  std::vector<std::shared_ptr<const Irregularity>> profile_irregularity(profiles.size());
  if (!facts.empty()) profile_irregularity[0] = facts.front().first_scene.irregularity;
  for (std::size_t j = 1; j < profiles.size(); ++j)
    profile_irregularity[j] =
        parse(scene_doc(structures.front(), variants.front(), trains[0], first_speed_kmh, profiles[j].value,
                        placeholder_dt_s),
              train_paths[0], profiles[j].path, structures.front())
            .irregularity;

  std::vector<std::string> train_labels;
  for (const json& t : trains) train_labels.push_back(study_train_label(t));
  make_unique(train_labels);

  plan.jobs.reserve(count);
  for (const NamedStructure& s : structures)
    if (!s.name.empty()) plan.structures.push_back(s.name);
  // Where each job is in plan.jobs: a bridge listed twice (the same
  // structure under two names) shares its jobs.
  std::map<std::string, std::size_t> ids;
  for (std::size_t n = 0; n < facts.size(); ++n) {
    const std::size_t i = n % trains.size();
    const StructureVariant& variant = variants[(n / trains.size()) % variants.size()];
    const std::size_t structure_index = n / (trains.size() * variants.size());
    const NamedStructure& structure = structures[structure_index];
    const TrainFacts& f = facts[n];
    std::string modal_key;
    double modal_key_dt_s = 0.0;
    // The scene text of each profile around its speed, for the dt it was made at.
    std::vector<std::optional<CanonicalNumberSlot>> slots(profiles.size());
    std::vector<double> slot_dt_s(profiles.size(), 0.0);
    for (double speed_kmh : f.speeds_kmh) {
      for (std::size_t k = 0; k < profiles.size(); ++k) {
        Scene at_speed = f.first_scene;
        at_speed.speed_mps = speed_kmh / 3.6;
        at_speed.irregularity = profile_irregularity[k];
        const JobTimeStep dt = job_time_step(dt_given, at_speed, f.frequencies, f.plan);
        at_speed.analysis.dt_s = dt.dt_s;
        const bool modal = f.plan.rung.structure == "modal" || f.plan.rung.structure == "hybrid";
        ScenePlan on_rung;
        on_rung.rung = f.plan.rung;
        on_rung.modal_cutoff_hz = f.plan.modal_cutoff_hz;
        apply_rung_structure(on_rung, at_speed.analysis);
        // The modal key hashes the rail lines and outputs: computed once per
        // train and dt (one dt for all its speeds on the exact modal rung).
        if (f.plan.rung.exact_modal() && !(modal_key_dt_s == dt.dt_s && !modal_key.empty())) {
          modal_key = modal_operator_key(f.structure_hash, *f.structure, f.plan.modal_cutoff_hz, dt.dt_s);
          modal_key_dt_s = dt.dt_s;
        }
        const std::string key = f.plan.rung.exact_modal()
                                    ? modal_key
                                    : operator_key(f.structure_hash, at_speed.analysis, f.rail_flexibility);
        const Profile& p = profiles[k];
        JobSpec job;
        const auto scene_at = [&](double at_speed_kmh) {
          json scene = scene_doc(structure, variant, trains[i], at_speed_kmh, p.value, dt.dt_s);
          // The job runs without the frequencies: the free vibration they
          // give (max(1 s, 3 periods of f0)) is written into its scene.
          if (!scene["analysis"].contains("free_vibration_s"))
            scene["analysis"]["free_vibration_s"] = free_vibration_s(f.first_scene.analysis);
          if (auto_fidelity) scene["fidelity"] = f.fidelity;
          else if (modal && !scene["fidelity"].contains("modal_cutoff_hz"))
            scene["fidelity"]["modal_cutoff_hz"] = f.plan.modal_cutoff_hz;  // the job runs without the frequencies
          return scene;
        };
        if (!slots[k] || slot_dt_s[k] != dt.dt_s) {
          slots[k] = CanonicalNumberSlot::make(scene_at(speed_kmh), "speed_kmh");
          slot_dt_s[k] = dt.dt_s;
        }
        job.scene = slots[k] ? slots[k]->text(speed_kmh) : canonical_text(scene_at(speed_kmh));
        job.id = sha256_hex(job.scene);
        // The same scene listed twice is one job (on each bridge it stands for).
        if (const auto [it, fresh] = ids.try_emplace(job.id, plan.jobs.size()); !fresh) {
          std::vector<int>& on = plan.jobs[it->second].structures;
          if (!structure.name.empty() && std::find(on.begin(), on.end(), static_cast<int>(structure_index)) == on.end())
            on.push_back(static_cast<int>(structure_index));
          continue;
        }
        if (!structure.name.empty()) job.structures.push_back(static_cast<int>(structure_index));
        job.train = train_labels[i];
        job.speed_kmh = speed_kmh;
        job.irregularity = p.label;
        job.variant = variant_label(variant);
        job.operator_key = key;
        job.dt_s = dt.dt_s;
        job.dt_reason = dt.reason;
        job.cutoff_hz = f.cutoff_hz;
        job.rung = f.plan.rung.name();
        job.modes = f.modes;
        job.hybrid_modes = f.hybrid_modes;
        plan.jobs.push_back(std::move(job));
      }
    }
  }
  return plan;
}

StudyPlan load_study(const std::filesystem::path& file, const ExpandOptions& options) {
  return expand_study(read_json_file(file), file.parent_path(), file.string(), options);
}

}  // namespace railvsi::scheduler

#include "io/scene_loader.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/irregularity_loader.hpp"
#include "io/json_document.hpp"
#include "io/schema_validator.hpp"
#include "io/structure_loader.hpp"
#include "io/train_loader.hpp"
#include "simulation/simulation.hpp"
#include "solver/hybrid_basis.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

// Consistent beta and gamma unless both are given; a pair that amplifies
// the response (such as the paper's printed 9/20 and 9025/40000) is refused.
HhtParameters hht_parameters(const json& a) {
  const double alpha = a.value("hht_alpha", AnalysisOptions{}.hht.alpha);
  const bool has_beta = a.contains("hht_beta"), has_gamma = a.contains("hht_gamma");
  if (has_beta != has_gamma)
    throw InputError(has_beta ? "/analysis/hht_gamma" : "/analysis/hht_beta",
                     "hht_beta and hht_gamma must be given together (or neither, for the consistent pair)");
  const HhtParameters p = has_beta ? HhtParameters{alpha, a.at("hht_beta").get<double>(), a.at("hht_gamma").get<double>()}
                                   : HhtParameters::from_alpha(alpha);
  if (const auto problem = hht_stability_problem(p))
    throw InputError(has_beta ? "/analysis/hht_beta" : "/analysis/hht_alpha", *problem);
  return p;
}

ContactOptions contact_options(const json& c) {
  ContactOptions o;
  if (c.contains("law")) o.law = c.at("law").get<std::string>();
  if (c.contains("unilateral")) o.unilateral = c.at("unilateral").get<bool>();
  if (c.contains("G_m_per_N23")) o.hertz_G = c.at("G_m_per_N23").get<double>();
  o.wheels_per_contact = c.value("wheels_per_contact", o.wheels_per_contact);
  if (c.contains("rail_lines")) o.rail_lines = c.at("rail_lines").get<std::vector<int>>();
  (void)make_contact_law(o);  // the law checks its own options (InputError with the path)
  return o;
}

double speed_mps(const json& doc, const AnalysisOptions& analysis) {
  const double speed_kmh = doc.at("speed_kmh").get<double>();
  if (speed_kmh == 0.0 && !analysis.duration_s)
    throw InputError("/speed_kmh", "a speed of 0 needs analysis.duration_s (the train would never leave the bridge)");
  if (speed_kmh != 0.0 && !(speed_kmh >= 1.0 && speed_kmh <= 1000.0))
    throw InputError("/speed_kmh", fmt::format("{:g} km/h is not a train speed: give 0 (with analysis.duration_s) or "
                                               "a speed in [1, 1000] km/h",
                                               speed_kmh));
  return speed_kmh / 3.6;
}

Train scene_train(const json& train) {
  return with_path_prefix("/train", [&] { return parse_train_reference(train); });
}

// Where the wheels run: the whole train behind the rail start (or behind an
// explicit start), the rail line, and past its end until the last axle has
// left the evaluation window. A generated profile covers all of it, so that no
// wheel meets the step where a profile ends.
TrackRange wheel_range(const Scene& scene) {
  const RailLine& rail = scene.structure->rails().front();
  const double reach_m = scene.train.length_m() + 10.0;
  const double start_m = std::min(rail.start_m(), scene.start_x_m.value_or(rail.start_m())) - reach_m;
  // And the free vibration's travel: the given time, or the default rule for
  // any f0 >= 1 Hz (f0 is not known here).
  const AnalysisOptions& a = scene.analysis;
  const double free_s = a.free_vibration_s.value_or(std::max(a.free_vibration_min_s, a.free_vibration_periods / 1.0));
  const double free_m = scene.speed_mps * (free_s + a.extra_time_s);
  return {start_m, std::max(rail.end_m() + a.evaluation_margin_m, track_exit_m(scene)) + reach_m + free_m};
}

// After the structure and the train: a spectrum is sampled over their wheel_range.
std::shared_ptr<const Irregularity> scene_irregularity(const json& doc, const std::filesystem::path& base_dir,
                                                       const Scene& scene) {
  const auto it = doc.find("irregularity");
  if (it == doc.end() || it->is_null()) return nullptr;
  return with_path_prefix("/irregularity", [&] { return parse_irregularity(*it, base_dir, wheel_range(scene)); });
}

// "fidelity", "accuracy" and "asks" of a scene or study; a pinned contact
// law overrides the analysis's (checked again by the law itself).
FidelityRequest fidelity_request(const json& doc, const Train& train, ContactOptions& contact) {
  FidelityRequest f;
  if (doc.contains("accuracy")) f.tolerance = doc.at("accuracy").value("tolerance", f.tolerance);
  if (doc.contains("asks")) f.asks = doc.at("asks").get<std::vector<std::string>>();
  const auto it = doc.find("fidelity");
  if (it == doc.end()) return f;
  if (it->is_string()) {
    f.mode = FidelityRequest::Mode::kAuto;
    return f;
  }
  f.mode = FidelityRequest::Mode::kPinned;
  const json& r = *it;
  f.model = r.at("model").get<std::string>();
  f.structure = r.at("structure").get<std::string>();
  if (f.model == "moving_forces" && !train.is_moving_forces())
    throw InputError("/fidelity/model", "moving_forces needs a train of axle loads; this train has vehicles (give "
                                        "{\"library\": name, \"as\": \"moving_forces\"} for its static axle loads)");
  if (f.model == "interaction" && train.is_moving_forces())
    throw InputError("/fidelity/model", "interaction needs multibody vehicles; this train is axle loads");
  if (r.contains("contact_law")) contact.law = r.at("contact_law").get<std::string>();
  if (r.contains("unilateral")) contact.unilateral = r.at("unilateral").get<bool>();
  if (r.contains("contact_law") || r.contains("unilateral"))
    with_path_prefix("/fidelity", [&] { return make_contact_law(contact); });
  if (r.contains("modal_cutoff_hz")) f.modal_cutoff_hz = r.at("modal_cutoff_hz").get<double>();
  if (r.contains("escalate_below_fraction")) f.escalate_below_fraction = r.at("escalate_below_fraction").get<double>();
  if (r.contains("escalation_dt_factor")) f.escalation_dt_factor = r.at("escalation_dt_factor").get<double>();
  if (r.contains("reasons")) f.reasons = r.at("reasons").get<std::vector<std::string>>();
  return f;
}

// Interaction on the modes of a structure with track misses any tolerance:
// the track's own modes (rail on pads near 150 Hz; sleeper passing at 139 Hz
// at 300 km/h) respond where the wheel forces have their content, and the
// pads' and ballast's dampers couple the modes.
void refuse_modal_interaction_on_track(const Scene& scene) {
  if (scene.train.is_moving_forces()) return;
  const bool pinned = scene.fidelity.mode == FidelityRequest::Mode::kPinned;
  const bool modal = pinned ? scene.fidelity.structure == "modal"
                            : scene.analysis.structure_backend == StructureBackend::kModal;
  if (!modal || !hybrid_partition(*scene.structure).unavailable.empty()) return;
  throw InputError(pinned ? "/fidelity/structure" : "/analysis/structure",
                   "interaction on the modal structure is refused on a structure with track: against the FE "
                   "structure its filtered deck acceleration was measured 10 % to 84 % off on a ballasted viaduct "
                   "(modes up to 60-200 Hz, with or without the static correction), because the track's own modes respond where the wheel forces "
                   "have their content; use \"hybrid\" (the track in FE, the bridge in its modes) or \"fe\"");
}

}  // namespace

AnalysisOptions parse_analysis(const json& a) {
  AnalysisOptions o;
  o.dt_s = a.at("dt_s").get<double>();
  // Checked here rather than by the schema's minimum, whose message prints 1e-7 as 0.000000.
  if (!(o.dt_s >= 1e-7))
    throw InputError("/analysis/dt_s", fmt::format("dt_s = {:g} s is below 1e-7 s: not a plausible time step", o.dt_s));
  o.hht = hht_parameters(a);
  if (a.contains("solver"))
    o.solver = a.at("solver").get<std::string>() == "reference" ? SolverPath::kReference : SolverPath::kCondensed;
  if (a.contains("contact")) o.contact = contact_options(a.at("contact"));
  if (a.contains("structure")) {
    // The schema allows only the backends' names.
    if (const auto backend = parse_structure_backend(a.at("structure").get<std::string>()))
      o.structure_backend = *backend;
  }
  o.modal_modes = a.value("modes", o.modal_modes);
  o.modal_cutoff_hz = a.value("cutoff_hz", o.modal_cutoff_hz);
  if ((a.contains("modes") || a.contains("cutoff_hz")) && o.structure_backend == StructureBackend::kFiniteElements)
    throw InputError(a.contains("modes") ? "/analysis/modes" : "/analysis/cutoff_hz",
                     "modes and cutoff_hz choose the modes of the modal or hybrid structure: give \"structure\": "
                     "\"modal\" or \"hybrid\"");
  o.modal_static_correction = a.value("static_correction", o.modal_static_correction);
  if (a.contains("static_correction") && o.structure_backend != StructureBackend::kModal)
    throw InputError("/analysis/static_correction",
                     "static_correction corrects the modes of the modal structure: give \"structure\": \"modal\"");
  if (a.contains("modes") && a.contains("cutoff_hz"))
    throw InputError("/analysis/cutoff_hz", "give either modes or cutoff_hz, not both");
  o.max_newton_iterations = a.value("max_newton_iterations", o.max_newton_iterations);
  o.newton_tolerance = a.value("newton_tolerance", o.newton_tolerance);
  if (a.contains("duration_s")) o.duration_s = a.at("duration_s").get<double>();
  if (a.contains("free_vibration_s")) o.free_vibration_s = a.at("free_vibration_s").get<double>();
  o.evaluation_margin_m = a.value("evaluation_margin_m", o.evaluation_margin_m);
  o.extra_time_s = a.value("extra_time_s", o.extra_time_s);
  o.history_stride = a.value("history_stride", o.history_stride);
  return o;
}

Scene parse_scene(const json& doc, const std::filesystem::path& base_dir, const std::string& file_for_errors,
                  ImportedStructures* imports, const std::string& content_key) {
  return parse_validated(doc, "scene.schema.json", file_for_errors, [&] {
    Scene scene;
    // Cheap checks first: a typo in the analysis should not wait for a big import.
    scene.analysis = parse_analysis(doc.at("analysis"));
    if (doc.at("analysis").contains("start_x_m")) scene.start_x_m = doc.at("analysis").at("start_x_m").get<double>();
    scene.speed_mps = speed_mps(doc, scene.analysis);
    scene.train = scene_train(doc.at("train"));
    scene.fidelity = fidelity_request(doc, scene.train, scene.analysis.contact);
    scene.structure =
        parse_structure(doc.at("structure"), doc.value("outputs", json::object()), base_dir, scene.train, imports,
                        content_key);
    scene.irregularity = scene_irregularity(doc, base_dir, scene);
    refuse_modal_interaction_on_track(scene);
    return scene;
  });
}

Scene load_scene(const std::filesystem::path& file) {
  return parse_scene(read_json_file(file), file.parent_path(), file.string());
}

}  // namespace railvsi

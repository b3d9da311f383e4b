// vsi inspect: the models of a scene, study, train or irregularity document in
// numbers an engineer checks before trusting them.
#include <algorithm>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/commands.hpp"
#include "study/study_structures.hpp"
#include "cli/inspect_report.hpp"
#include "io/document_kind.hpp"
#include "io/irregularity_loader.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "io/schema_validator.hpp"
#include "io/train_loader.hpp"
#include "io/train_sets.hpp"
#include "core/terminal_text.hpp"
#include "core/types.hpp"
#include "planning/deck_frequencies.hpp"
#include "study/speed_list.hpp"

namespace railvsi::cli {
namespace {

using nlohmann::ordered_json;

// Speeds a scene's or a study's resonance list covers when the study does
// not bound them: the HSLM range of EN 1991-2 practice, at most 1.2 x 350 km/h.
constexpr double kResonanceMinKmh = 40.0, kResonanceMaxKmh = 420.0;

double fundamental_hz(const StructureModel& structure) { return deck_frequencies(structure).f0_hz; }

// A study: its structure (with the first train on it), the lowest modes,
// every train in short, the speeds, and the HSLM resonance speeds within
// the study's speed range.
ordered_json study_report(const nlohmann::json& given, const std::filesystem::path& file, int modes) {
  shared_schema_validator("study.schema.json").validate(given, file.string());
  nlohmann::json doc = given;
  std::vector<std::string> train_paths;  // each train's place in the given study
  doc["trains"] = expand_train_sets(given.at("trains"), file.string(), &train_paths);
  // The given speeds and the steps of a line_speed_kmh range (its speeds
  // around the resonances are listed with the resonance speeds below).
  std::vector<double> speeds;
  if (doc.contains("speeds_kmh")) speeds = scheduler::expand_speeds(doc.at("speeds_kmh"), 100000);
  if (const auto range = scheduler::line_speed_range(doc)) {
    const std::vector<double> steps = scheduler::line_speed_speeds(*range, 0.0, 0.0, 0.0, 100000);
    speeds.insert(speeds.end(), steps.begin(), steps.end());
    std::sort(speeds.begin(), speeds.end());
  }
  if (speeds.empty()) throw InputError("/speeds_kmh", "give speeds_kmh, line_speed_kmh or both", file.string());
  ordered_json report;
  report["file"] = file.string();
  report["document"] = "study";
  report["name"] = doc.contains("name") ? doc.at("name").get<std::string>() : file.filename().string();
  // A line study: its first bridge stands for the structure here.
  const std::vector<scheduler::NamedStructure> structures =
      scheduler::study_structures(doc, file.parent_path(), file.string());
  if (!structures.front().name.empty()) {
    ordered_json names = ordered_json::array();
    for (const auto& s : structures) names.push_back(s.name);
    report["structures"] = names;
  }
  ordered_json trains = ordered_json::array(), resonances = ordered_json::array();
  double f0_hz = 0.0;
  for (std::size_t i = 0; i < doc.at("trains").size(); ++i) {
    nlohmann::json scene = {{"structure", structures.front().structure},
                            {"train", doc.at("trains")[i]},
                            {"speed_kmh", speeds.front()},
                            {"irregularity", nullptr},
                            {"analysis", doc.contains("analysis") ? doc.at("analysis") : nlohmann::json::object()}};
    if (!scene["analysis"].contains("dt_s")) scene["analysis"]["dt_s"] = 1e-3;  // not used: no run
    if (doc.contains("outputs")) scene["outputs"] = doc.at("outputs");
    if (!structures.front().outputs.is_null()) scene["outputs"] = structures.front().outputs;
    Scene parsed = [&] {
      try {
        return parse_scene(scene, file.parent_path(), file.string());
      } catch (const InputError& e) {
        const std::string& path = e.json_path();
        if (path.starts_with("/train")) throw InputError(train_paths[i] + path.substr(6), e.what(), file.string());
        throw e.with_file(file.string());
      }
    }();
    if (i == 0) {
      report["structure"] = structure_report(*parsed.structure);
      report["modal_analysis"] = modal_report(*parsed.structure, modes);
      f0_hz = fundamental_hz(*parsed.structure);
    }
    trains.push_back(train_report(parsed.train));
    const ordered_json r = resonance_report(parsed.train, f0_hz, speeds.front(), speeds.back());
    if (!r.is_null()) resonances.push_back(r);
  }
  report["trains"] = trains;
  report["speeds_kmh"] = speeds;
  report["f0_hz"] = f0_hz;
  report["resonance_speeds"] = resonances;
  return report;
}

ordered_json build_report(const std::filesystem::path& file, int modes) {
  const nlohmann::json doc = read_json_file(file);
  if (cli::is_study_document(doc)) return study_report(doc, file, modes);
  const DocumentKind kind = detect_document_kind(doc, file.string());
  ordered_json report;
  report["file"] = file.string();
  report["document"] = std::string(document_kind_name(kind));
  // Engine checks (a vehicle its wheels do not carry) are input errors of this file.
  try {
    switch (kind) {
      case DocumentKind::kScene: {
        const Scene scene = parse_scene(doc, file.parent_path(), file.string());
        report["structure"] = structure_report(*scene.structure);
        report["modal_analysis"] = modal_report(*scene.structure, modes);
        report["train"] = train_report(scene.train);
        report["speed_kmh"] = scene.speed_mps * 3.6;
        report["irregularity"] = scene.irregularity ? irregularity_report(*scene.irregularity) : ordered_json(nullptr);
        if (scene.train.coach_length_m > 0.0) {
          const double f0_hz = fundamental_hz(*scene.structure);
          report["f0_hz"] = f0_hz;
          report["resonance_speeds"] = ordered_json::array(
              {resonance_report(scene.train, f0_hz, kResonanceMinKmh, kResonanceMaxKmh)});
        }
        break;
      }
      case DocumentKind::kTrain:
        report["train"] = train_report(parse_train_document(doc, file));
        // Where the numbers come from, to check them against the source.
        for (const char* key : {"sources", "assumptions"})
          if (doc.contains(key)) report["train"][key] = doc.at(key);
        break;
      case DocumentKind::kIrregularity:
        report["irregularity"] = irregularity_report(*parse_irregularity_document(doc, file));
        break;
    }
  } catch (const InputError& e) {
    throw e.with_file(file.string());
  }
  return report;
}

std::string optional_number(const ordered_json& v, const char* format_spec, double scale = 1.0) {
  return v.is_number() ? fmt::format(fmt::runtime(format_spec), v.get<double>() * scale) : "unknown";
}

void print_structure(const ordered_json& s, std::ostream& out) {
  out << fmt::format("structure ({}): {} DOFs = {} deck + {} track\n", scheduler::terminal_safe(s["source"].get<std::string>()),
                     s["dofs"].get<int>(), s["deck_dofs"].get<int>(), s["track_dofs"].get<int>());
  for (const auto& r : s["rail_lines"])
    out << fmt::format("  rail line '{}': {} nodes, x from {:.3f} to {:.3f} m\n", scheduler::terminal_safe(r["name"].get<std::string>()),
                       r["nodes"].get<int>(), r["start_m"].get<double>(), r["end_m"].get<double>());
  out << fmt::format("  bridge: {:.3f} to {:.3f} m", s["bridge_start_m"].get<double>(), s["bridge_end_m"].get<double>());
  if (!s["supports_m"].empty())
    out << fmt::format(", supports at {} m", fmt::join(s["supports_m"].get<std::vector<double>>(), ", "));
  out << '\n';
  out << fmt::format("  damping: {} % ({})\n", optional_number(s["damping_ratio"], "{:.3f}", 100.0),
                     scheduler::terminal_safe(s["damping_source"].get<std::string>()));
  for (const auto& p : s["output_points"])
    out << fmt::format("  output point '{}' at x = {:.3f} m\n", scheduler::terminal_safe(p["name"].get<std::string>()), p["x_m"].get<double>());
  if (!s["import"].is_null()) {
    out << "  import:\n";
    for (const auto& line : s["import"]["matched"]) out << "    " << scheduler::terminal_safe(line.get<std::string>()) << '\n';
    for (const auto& line : s["import"]["warnings"]) out << "    warning: " << scheduler::terminal_safe(line.get<std::string>()) << '\n';
  }
}

void print_modes(const ordered_json& m, std::ostream& out) {
  out << "natural frequencies of the structure alone (no train mass):\n";
  if (m["status"] != "ok") {
    out << fmt::format("  modal analysis failed ({}): {}\n", m["status"].get<std::string>(),
                       m["message"].get<std::string>());
    return;
  }
  if (m.contains("units_warning")) out << "  warning: " << m["units_warning"].get<std::string>() << '\n';
  if (m.contains("supports_from_modes")) {
    std::string at;
    for (const auto& x : m["supports_from_modes"]["supports_m"])
      at += fmt::format("{}{:.2f}", at.empty() ? "" : ", ", x.get<double>());
    out << "  supports [m]: " << at << " (" << m["supports_from_modes"]["note"].get<std::string>() << ")\n";
  }
  if (m.contains("solver")) out << "  solver: " << m["solver"].get<std::string>() << '\n';
  out << "     n   frequency_hz  deck_energy  type\n";
  for (const auto& mode : m["modes"])
    out << fmt::format("  {:4d}  {:13.4f}  {:10.1f}%  {}\n", mode["n"].get<int>(), mode["frequency_hz"].get<double>(),
                       100.0 * mode["deck_energy_fraction"].get<double>(), mode["type"].get<std::string>());
}

void print_train_summary(const ordered_json& t, std::ostream& out) {
  // The mass a designer compares with a data sheet: the load over the g of
  // the static wheel loads.
  out << fmt::format("train '{}' ({}): {} axles over {:.3f} m (first to last), total static load {:.1f} kN ({:.1f} t)\n",
                     scheduler::terminal_safe(t["name"].get<std::string>()), t["model"].get<std::string>(), t["axles"].get<int>(),
                     t["length_m"].get<double>(), t["total_static_load_N"].get<double>() / 1e3,
                     t["total_static_load_N"].get<double>() / kGravity_mps2 / 1e3);
  if (t.contains("vehicles"))
    out << fmt::format("  {} vehicles, {} DOFs, total mass {:.1f} t\n", t["vehicles"].get<int>(),
                       t["vehicle_dofs"].get<int>(), t["total_mass_kg"].get<double>() / 1e3);
}

void print_train(const ordered_json& t, std::ostream& out) {
  print_train_summary(t, out);
  for (const char* key : {"sources", "assumptions"})
    if (t.contains(key))
      for (const auto& line : t[key]) out << "  " << key << ": " << scheduler::terminal_safe(line.get<std::string>()) << '\n';
  out << "  axle    offset_m  static_load_kN\n";
  int n = 0;
  for (const auto& a : t["axle_list"])
    out << fmt::format("  {:4d}  {:10.3f}  {:14.2f}{}\n", ++n, a["offset_m"].get<double>(),
                       a["static_load_N"].get<double>() / 1e3,
                       a.contains("vehicle") ? "  " + scheduler::terminal_safe(a["vehicle"].get<std::string>()) : std::string());
}

void print_irregularity(const ordered_json& r, std::ostream& out) {
  if (r.is_null()) {
    out << "irregularity: none (perfect track)\n";
    return;
  }
  out << fmt::format("irregularity '{}': {} samples, x from {:.3f} to {:.3f} m\n", scheduler::terminal_safe(r["source"].get<std::string>()),
                     r["samples"].get<int>(), r["x_start_m"].get<double>(), r["x_end_m"].get<double>());
  out << fmt::format("  r min {:.3f} mm, max {:.3f} mm, mean {} mm, RMS {} mm\n", r["min_m"].get<double>() * 1e3,
                     r["max_m"].get<double>() * 1e3, optional_number(r["mean_m"], "{:.3f}", 1e3),
                     optional_number(r["rms_m"], "{:.3f}", 1e3));
}

void print_resonances(const ordered_json& report, std::ostream& out) {
  if (!report.contains("resonance_speeds")) return;
  out << fmt::format("HSLM resonance speeds v = f0 D / i (f0 = {:.3f} Hz; EN 1991-2 Annex E trains):\n",
                     report["f0_hz"].get<double>());
  if (report["resonance_speeds"].empty()) out << "  none: no HSLM-A train\n";
  for (const auto& r : report["resonance_speeds"]) {
    std::string list;
    for (const auto& s : r["speeds"])
      list += fmt::format("{}i={}: {:.1f}", list.empty() ? "" : ", ", s["i"].get<int>(), s["speed_kmh"].get<double>());
    out << fmt::format("  {} (D = {:g} m): {} km/h\n", scheduler::terminal_safe(r["train"].get<std::string>()),
                       r["coach_length_m"].get<double>(), list.empty() ? "none in the speed range" : list);
  }
}

void print_text(const ordered_json& report, std::ostream& out) {
  out << fmt::format("{} ({})\n", scheduler::terminal_safe(report["file"].get<std::string>()),
                     report["document"].get<std::string>());
  if (report.contains("name")) out << fmt::format("study '{}'\n", scheduler::terminal_safe(report["name"].get<std::string>()));
  if (report.contains("structure")) print_structure(report["structure"], out);
  if (report.contains("modal_analysis")) print_modes(report["modal_analysis"], out);
  if (report.contains("train")) print_train(report["train"], out);
  if (report.contains("trains"))
    for (const auto& t : report["trains"]) print_train_summary(t, out);
  if (report.contains("speeds_kmh") && report["speeds_kmh"].is_array()) {
    const auto v = report["speeds_kmh"].get<std::vector<double>>();
    out << fmt::format("speeds: {} from {:g} to {:g} km/h\n", v.size(), v.front(), v.back());
  }
  if (report.contains("speed_kmh")) out << fmt::format("speed: {:.1f} km/h\n", report["speed_kmh"].get<double>());
  print_resonances(report, out);
  if (report.contains("irregularity")) print_irregularity(report["irregularity"], out);
}

}  // namespace

int inspect_command(const InspectArgs& args) {
  const ordered_json report = build_report(args.file, args.modes);
  if (args.format == "json")
    std::cout << report.dump(2) << '\n';
  else
    print_text(report, std::cout);
  const bool modal_ok = !report.contains("modal_analysis") || report["modal_analysis"]["status"] == "ok";
  return modal_ok ? kExitOk : kExitRuntimeFailure;
}

}  // namespace railvsi::cli

#include <iostream>

#include "analysis/frequency_units_check.hpp"
#include "solver/modal_analysis.hpp"
#include "cli/commands.hpp"
#include "core/terminal_text.hpp"
#include "io/document_kind.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "model/undamped_structure.hpp"
#include "simulation/simulation.hpp"
#include "study/study_plan.hpp"

namespace railvsi::cli {

bool is_study_document(const nlohmann::json& doc) {
  if (!doc.is_object()) return false;
  if (doc.contains("$schema") && doc.at("$schema").is_string())
    return doc.at("$schema").get<std::string>().ends_with("study.schema.json");
  return doc.contains("trains");
}

namespace {

// An imported model's warnings (stderr; the document is still valid): what
// the import noticed, and a first frequency that suggests a unit mistake.
void warn_about_import(const StructureModel& structure, const std::string& file) {
  if (structure.info().source != "import") return;
  for (const std::string& w : structure.info().import_warnings)
    std::cerr << "warning: " << scheduler::terminal_safe(file) << ": /structure/import: " << w << '\n';
  if (structure_undamped(structure.info()))
    std::cerr << "warning: " << scheduler::terminal_safe(file) << ": /structure/damping: " << kUndampedStructureWarning
              << '\n';
  ModalOptions options;
  options.modes = 1;
  const ModalResult modes = modal_analysis(structure, options);
  if (modes.status.ok() && !modes.frequencies_hz.empty())
    if (const auto w = frequency_units_warning(modes.frequencies_hz.front()))
      std::cerr << "warning: " << scheduler::terminal_safe(file) << ": /structure/import: " << *w << '\n';
}

}  // namespace

void require_study_file(const std::string& file) {
  const nlohmann::json doc = read_json_file(file);
  if (is_study_document(doc)) return;
  DocumentKind kind{};
  try {
    kind = detect_document_kind(doc, file);
  } catch (const InputError&) {
    return;  // neither a study nor another document: the study schema says what is wrong
  }
  const std::string what = kind == DocumentKind::kScene
                               ? "this is a scene, not a study: run it with `vsi simulate " + file + "`"
                               : "this is a" + std::string(kind == DocumentKind::kIrregularity ? "n " : " ") +
                                     std::string(document_kind_name(kind)) +
                                     " document, not a study (a study lists trains, speeds_kmh and a structure: "
                                     "schemas/study.schema.json)";
  throw InputError("/", what, file);
}

int validate_command(const std::string& file) {
  if (is_study_document(read_json_file(file))) {
    // Everything vsi submit checks, without a database.
    const scheduler::StudyPlan plan = scheduler::load_study(file);
    std::cout << scheduler::terminal_safe(file) << ": ok (study, " << plan.jobs.size() << " jobs)\n";
    return kExitOk;
  }
  const DocumentKind kind = validate_document(file);
  if (kind == DocumentKind::kScene) {
    // A dry run of the setup: factorization (mechanism check) and the static
    // equilibrium of the train, everything but the time loop.
    try {
      const Scene scene = load_scene(file);
      const Simulation setup(scene);
      warn_about_import(*scene.structure, file);
    } catch (const InputError& e) {
      throw e.with_file(file);
    }
  }
  std::cout << scheduler::terminal_safe(file) << ": ok (" << document_kind_name(kind) << ")\n";
  return kExitOk;
}

}  // namespace railvsi::cli

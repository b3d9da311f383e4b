#include <iostream>

#include "analysis/frequency_units_check.hpp"
#include "analysis/modal_analysis.hpp"
#include "cli/commands.hpp"
#include "io/document_kind.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"
#include "study/study_plan.hpp"

namespace railvsi::cli {

namespace {

// A study names study.schema.json in "$schema" or lists "trains"; the
// engine's document kinds know nothing of studies.
bool is_study(const std::string& file) {
  const nlohmann::json doc = read_json_file(file);
  if (!doc.is_object()) return false;
  if (doc.contains("$schema") && doc.at("$schema").is_string())
    return doc.at("$schema").get<std::string>().ends_with("study.schema.json");
  return doc.contains("trains");
}

// An imported model's warnings (stderr; the document is still valid): what
// the import noticed, and a first frequency that suggests a unit mistake.
void warn_about_import(const StructureModel& structure, const std::string& file) {
  if (structure.info().source != "import") return;
  for (const std::string& w : structure.info().import_warnings)
    std::cerr << "warning: " << file << ": /structure/import: " << w << '\n';
  ModalOptions options;
  options.modes = 1;
  const ModalResult modes = modal_analysis(structure, options);
  if (modes.status.ok() && !modes.frequencies_hz.empty())
    if (const auto w = frequency_units_warning(modes.frequencies_hz.front()))
      std::cerr << "warning: " << file << ": /structure/import: " << *w << '\n';
}

}  // namespace

int validate_command(const std::string& file) {
  if (is_study(file)) {
    // Everything vsi submit checks, without a database.
    const scheduler::StudyPlan plan = scheduler::load_study(file);
    std::cout << file << ": ok (study, " << plan.jobs.size() << " jobs)\n";
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
  std::cout << file << ": ok (" << document_kind_name(kind) << ")\n";
  return kExitOk;
}

}  // namespace railvsi::cli

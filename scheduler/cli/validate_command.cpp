#include <iostream>

#include "cli/commands.hpp"
#include "io/document_kind.hpp"
#include "io/scene_loader.hpp"
#include "simulation/simulation.hpp"

namespace railvsi::cli {

int validate_command(const std::string& file) {
  const DocumentKind kind = validate_document(file);
  if (kind == DocumentKind::kScene) {
    // A dry run of the setup: factorization (mechanism check) and the static
    // equilibrium of the train, everything but the time loop.
    try {
      const Simulation setup(load_scene(file));
    } catch (const InputError& e) {
      throw e.with_file(file);
    }
  }
  std::cout << file << ": ok (" << document_kind_name(kind) << ")\n";
  return kExitOk;
}

}  // namespace railvsi::cli

// vsi replay: run a stored job again from its scene (job_scenes.scene, file names
// absolute), with the job's own code cut-off, so that its histories and
// summary reconcile with the envelopes the study stored.
#include <iostream>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/service_commands.hpp"
#include "cli/service_store.hpp"
#include "core/terminal_text.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"

namespace railvsi::cli {

int replay_command(const ReplayArgs& args) {
  if (args.job_id.size() < 6 || args.job_id.find_first_not_of("0123456789abcdef") != std::string::npos) {
    std::cerr << "error: job id " << scheduler::terminal_safe(args.job_id)
              << ": give the id or a prefix of at least 6 hex digits (vsi query --format json lists them)\n";
    return kExitInvalidInput;
  }
  const auto db = open_store(args.db);
  scheduler::Statement s =
      db->prepare("SELECT id, scene, cutoff_hz FROM job_records WHERE substr(id, 1, ?) = ? ORDER BY id LIMIT 2");
  s.bind(1, static_cast<std::int64_t>(args.job_id.size())).bind(2, args.job_id);
  if (!s.step()) {
    std::cerr << "error: no job " << args.job_id << " in " << scheduler::terminal_safe(db->file()) << '\n';
    return kExitInvalidInput;
  }
  const std::string id = s.text(0), scene_text = s.text(1);
  const double cutoff_hz = s.real(2);
  if (s.step()) {
    std::cerr << "error: job id prefix " << args.job_id << " is ambiguous: give more digits\n";
    return kExitInvalidInput;
  }
  const std::string label = fmt::format("job {}", id.substr(0, 12));
  const Scene scene = parse_scene(parse_json_text(scene_text, label), "/", label);
  return run_scene(scene, label, cutoff_hz, args.histories_dir);
}

}  // namespace railvsi::cli

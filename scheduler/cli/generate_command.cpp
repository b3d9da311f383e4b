#include "cli/generate_command.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "core/input_error.hpp"
#include "generators/deck_3d.hpp"
#include "io/deck_section_loader.hpp"
#include "io/json_document.hpp"
#include "io/structure_export.hpp"

namespace railvsi::cli {
namespace {

using nlohmann::ordered_json;

// The generator's option paths as the command-line options that set them.
InputError as_option_error(const InputError& e) {
  const std::string& path = e.json_path();
  for (const auto& [prefix, option] : {std::pair{"/target_dofs", "--dofs"}, std::pair{"/spans_m", "--spans"},
                                       std::pair{"/approach_m", "--approach"}})
    if (path.starts_with(prefix)) return InputError(option, e.what());
  return e;
}

ordered_json rail_lines_json(const StructureModel& model) {
  ordered_json lines = ordered_json::array();
  for (std::size_t r = 0; r < model.rails().size(); ++r) lines.push_back(r);
  return lines;
}

// HSLM-A1 as moving forces over the whole passage; half the load on each rail.
ordered_json moving_force_scene(const StructureModel& model, const std::string& summary) {
  return {{"$schema", "scene.schema.json"},
          {"description", fmt::format("HSLM-A1 (EN 1991-2 Annex E, library train) as moving forces at 300 km/h over "
                                      "the generated deck ({}); each axle load is split equally between the rails.",
                                      summary)},
          {"structure", {{"import", structure_import_json(model)}}},
          {"train", "HSLM-A1"},
          {"speed_kmh", 300},
          {"irregularity", nullptr},
          {"analysis", {{"dt_s", 1.0e-3}, {"contact", {{"rail_lines", rail_lines_json(model)}}}}}};
}

// The paper's run: KHST at 120 m/s, dt = 2.5e-4 s, 2,000 steps, HHT alpha = -0.05.
ordered_json multibody_scene(const StructureModel& model, const std::string& summary) {
  return {{"$schema", "scene.schema.json"},
          {"description",
           fmt::format("The seed-scale run of the paper (Neves, Montenegro, Azevedo & Calcada (2014), Engineering Structures 69, 83-89, section 5): the 46-axle "
                       "library train KHST (a KHST-like model, see jobs/trains/KHST.json) at 120 m/s (432 km/h), "
                       "dt = 2.5e-4 s, 2,000 steps, HHT alpha = -0.05, nonlinear Hertz contact, each wheelset on "
                       "both rails, over the generated deck ({}). The train starts wholly on the approach track.",
                       summary)},
          {"structure", {{"import", structure_import_json(model)}}},
          {"train", "KHST"},
          {"speed_kmh", 432},
          {"irregularity", nullptr},
          {"analysis",
           {{"dt_s", 2.5e-4},
            {"hht_alpha", -0.05},
            {"duration_s", 0.5},
            {"contact", {{"law", "hertz"}, {"rail_lines", rail_lines_json(model)}}}}}};
}

// At most this many DOFs: ten times the paper's size (a larger target
// searched meshes without end).
constexpr long kMaxGeneratedDofs = 5'000'000;
constexpr double kMaxSpanM = 200.0;

// "25,30,25": every field a span length in (0, 200] m; an empty field is an error.
std::vector<double> parse_spans(const std::string& text) {
  std::vector<double> spans;
  std::size_t start = 0;
  for (std::size_t k = 0;; ++k) {
    const std::size_t comma = text.find(',', start);
    const std::string field = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double v = 0.0;
    if (!CLI::detail::lexical_cast(field, v) || !std::isfinite(v) || v <= 0.0 || v > kMaxSpanM)
      throw InputError("--spans", fmt::format("span {} of '{}' is '{}': give span lengths in m in (0, {:g}], "
                                              "comma-separated",
                                              k + 1, text, field, kMaxSpanM));
    spans.push_back(v);
    if (comma == std::string::npos) return spans;
    start = comma + 1;
  }
}

}  // namespace

GenerateCommand::GenerateCommand(CLI::App& app) {
  generate_ = app.add_subcommand("generate", "Write a generated structure as Matrix Market files and a rail map, "
                                             "with example scenes");
  generate_->require_subcommand(1);
  CLI::App* deck = generate_->add_subcommand(
      "deck-3d", "Simply supported concrete spans (8-node hexahedra; solid, or a box girder with --section) with two "
                 "rails on pads, refined to a number of DOFs; writes K.mtx, M.mtx, C.mtx, map.json, moving_forces.json, multibody.json");
  deck->add_option("--dofs", args_.dofs,
                   "Total DOFs (deck and rails) the mesh is refined to, within 5 % (the paper's size is 233,292)")
      ->required()
      ->check(CLI::Range(1L, kMaxGeneratedDofs));
  deck->add_option("--out", args_.out_dir, "Directory for the files (created if needed; must be empty unless --force)")
      ->required();
  deck->add_flag("--force", args_.force, "Write into a non-empty --out, replacing the files of the same names");
  // Parsed by parse_spans: CLI11's delimiter dropped an empty field (25,,25 ran two spans).
  deck->add_option("--spans", args_.spans_text, "Span lengths in m, comma-separated (each in (0, 200]); default 25,25,25");
  deck->add_option("--approach", args_.approach_m, "Track on rigid ground before the bridge in m (holds the train "
                                                  "at the start), 0 to 2000")
      ->capture_default_str()
      ->check(finite_in(0.0, 2000.0));
  deck->add_option("--section", args_.section_file,
                   "Deck section document (schemas/deck-section.schema.json): a solid rectangle or a box girder; "
                   "default the solid 7 m x 1.6 m");
}

std::optional<int> GenerateCommand::run_parsed() const {
  if (!generate_->parsed()) return std::nullopt;
  GenerateArgs args = args_;
  if (!args.spans_text.empty()) args.spans_m = parse_spans(args.spans_text);
  return generate_deck_3d_command(args);
}

int generate_deck_3d_command(const GenerateArgs& args) {
  std::error_code ec;
  if (!args.force && std::filesystem::is_directory(args.out_dir, ec) &&
      !std::filesystem::is_empty(args.out_dir, ec))
    throw InputError("--out", fmt::format("{} is not empty; pass --force to write into it (files of the same "
                                          "names are replaced)",
                                          args.out_dir));
  if (!args.force && std::filesystem::exists(args.out_dir, ec) && !std::filesystem::is_directory(args.out_dir, ec))
    throw InputError("--out", fmt::format("{} exists and is not a directory", args.out_dir));
  Deck3dOptions o;
  o.target_dofs = static_cast<int>(std::min<long>(args.dofs, 1L << 30));
  o.spans_m = args.spans_m;
  o.approach_m = args.approach_m;
  if (!args.section_file.empty()) apply_deck_section_document(read_json_file(args.section_file), args.section_file, o);
  const Deck3d deck = [&] {
    try {
      return make_deck_3d(o);
    } catch (const InputError& e) {
      throw as_option_error(e);
    }
  }();
  const StructureModel& model = *deck.model;
  const std::string summary =
      fmt::format("{} DOFs: {} spans of {}, {} x {} x {} hexahedra per span, two rails on pads", model.num_dofs(),
                  o.spans_m.size(),
                  o.box ? fmt::format("a concrete box girder {} m wide, {} m deep", o.box->top_width_m, o.box->depth_m)
                        : fmt::format("{} m x {} m solid concrete", o.width_m, o.depth_m),
                  deck.mesh.nx.front(), deck.mesh.ny, deck.mesh.nz);
  std::vector<FileToWrite> files = structure_files(model);
  for (const auto& [name, scene] : {std::pair{"moving_forces.json", moving_force_scene(model, summary)},
                                    std::pair{"multibody.json", multibody_scene(model, summary)}})
    files.push_back({name, [text = scene.dump(2) + "\n"](const auto& file) { write_text_file(file, text); }});
  write_files_together(args.out_dir, files);

  ordered_json out = {{"dofs", model.num_dofs()},
                      {"target_dofs", args.dofs},
                      {"deck_dofs", model.info().deck_dofs},
                      {"rail_dofs", model.info().track_dofs},
                      {"mesh", {{"nx", deck.mesh.nx}, {"ny", deck.mesh.ny}, {"nz", deck.mesh.nz}}},
                      {"section",
                       {{"kind", o.box ? "box" : "solid"},
                        {"area_m2", deck.section_area_m2},
                        {"I_m4", deck.section_I_m4},
                        {"J_m4", deck.section_J_m4},
                        {"polar_m4", deck.section_polar_m4}}},
                      {"first_frequency_hz", model.info().first_frequency_hz},
                      {"files", ordered_json::array()}};
  for (const FileToWrite& f : files) out["files"].push_back(f.name);
  std::cout << out.dump(2) << '\n';
  return kExitOk;
}

}  // namespace railvsi::cli

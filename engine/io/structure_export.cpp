#include "io/structure_export.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "io/matrix_market.hpp"

namespace railvsi {
namespace {

nlohmann::ordered_json rail_line_json(const RailLine& line) {
  std::vector<int> dof_v, dof_rot;
  for (std::size_t e = 0; e < line.element_dofs.size(); ++e) {
    const auto& d = line.element_dofs[e];
    if (e > 0 && (line.element_dofs[e - 1][2] != d[0] || line.element_dofs[e - 1][3] != d[1]))
      throw std::invalid_argument(fmt::format("rail line '{}' has different DOFs on either side of node {}: the map "
                                              "format has one vertical and one rotation DOF per node",
                                              line.name, e));
    dof_v.push_back(d[0]);
    dof_rot.push_back(d[1]);
  }
  dof_v.push_back(line.element_dofs.back()[2]);
  dof_rot.push_back(line.element_dofs.back()[3]);
  return {{"name", line.name}, {"x_m", line.x_m}, {"dof_v", dof_v}, {"dof_rot", dof_rot}};
}

}  // namespace

nlohmann::ordered_json structure_map_json(const StructureModel& model) {
  const StructureInfo& info = model.info();
  nlohmann::ordered_json map;
  map["description"] = fmt::format("Written by railvsi from a '{}' model: {} DOFs ({} deck, {} track).", info.source,
                                    model.num_dofs(), info.deck_dofs, info.track_dofs);
  map["rail_lines"] = nlohmann::ordered_json::array();
  for (const RailLine& line : model.rails()) map["rail_lines"].push_back(rail_line_json(line));
  map["output_points"] = nlohmann::ordered_json::array();
  for (const OutputPoint& p : model.outputs())
    map["output_points"].push_back({{"name", p.name}, {"x_m", p.x_m}, {"dof", p.dof}});
  if (info.bridge_end_m > info.bridge_start_m) {
    map["bridge_start_m"] = info.bridge_start_m;
    map["bridge_end_m"] = info.bridge_end_m;
  }
  return map;
}

std::vector<FileToWrite> structure_files(const StructureModel& model) {
  const nlohmann::ordered_json map = structure_map_json(model);  // fails before anything is written
  std::vector<FileToWrite> files{
      {"K.mtx", [&model](const auto& file) { write_matrix_market(file, model.K()); }},
      {"M.mtx", [&model](const auto& file) { write_matrix_market(file, model.M()); }}};
  if (model.C().nonZeros() > 0)
    files.push_back({"C.mtx", [&model](const auto& file) { write_matrix_market(file, model.C()); }});
  files.push_back({"map.json", [map](const auto& file) { write_text_file(file, map.dump(1) + "\n"); }});
  return files;
}

nlohmann::ordered_json structure_import_json(const StructureModel& model) {
  nlohmann::ordered_json files = {{"K", "K.mtx"}, {"M", "M.mtx"}};
  if (model.C().nonZeros() > 0) files["C"] = "C.mtx";
  files["map"] = "map.json";
  return files;
}

}  // namespace railvsi

#include "io/structure_export.hpp"

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "io/abaqus_matrix.hpp"
#include "io/harwell_boeing.hpp"
#include "io/matrix_market.hpp"

namespace railvsi {
namespace {

constexpr int kVertical = 2, kRotation = 6;  // U2/UY and UR3/ROTZ: x along the track, y up

// One (vertical, rotation) DOF pair per node of a rail line.
struct NodeDofs {
  std::vector<int> v, rot;
};

NodeDofs node_dofs(const RailLine& line) {
  NodeDofs out;
  for (std::size_t e = 0; e < line.element_dofs.size(); ++e) {
    const auto& d = line.element_dofs[e];
    if (e > 0 && (line.element_dofs[e - 1][2] != d[0] || line.element_dofs[e - 1][3] != d[1]))
      throw std::invalid_argument(fmt::format("rail line '{}' has different DOFs on either side of node {}: the map "
                                              "format has one vertical and one rotation DOF per node",
                                              line.name, e));
    out.v.push_back(d[0]);
    out.rot.push_back(d[1]);
  }
  out.v.push_back(line.element_dofs.back()[2]);
  out.rot.push_back(line.element_dofs.back()[3]);
  return out;
}

nlohmann::ordered_json rail_line_json(const RailLine& line) {
  const NodeDofs d = node_dofs(line);
  return {{"name", line.name}, {"x_m", line.x_m}, {"dof_v", d.v}, {"dof_rot", d.rot}};
}

const char* extension(ExportFormat format) {
  switch (format) {
    case ExportFormat::kMatrixMarket: return ".mtx";
    case ExportFormat::kHarwellBoeing: return ".rsa";
    case ExportFormat::kAbaqus: return ".abq";
  }
  return "";
}

std::vector<int> track_dofs(const StructureModel& model) {
  std::vector<int> out;
  for (int i = 0; i < model.num_dofs(); ++i)
    if (model.info().is_track_dof(i)) out.push_back(i);
  return out;
}

// Made-up node labels of the equations, and the labelled map.
struct Labelled {
  std::vector<DofLabel> labels;
  std::map<long, std::pair<double, double>> xy;  // node -> (x, y) for nodes.csv
  nlohmann::ordered_json map;
};

Labelled labelled(const StructureModel& model, ExportFormat format) {
  const bool abaqus = format == ExportFormat::kAbaqus;
  const int n = model.num_dofs();
  // Rail DOF -> (line, node index, rotation?).
  struct RailRef {
    std::size_t line, node;
  };
  std::map<int, RailRef> rail_ref;
  std::vector<NodeDofs> rails;
  for (std::size_t r = 0; r < model.rails().size(); ++r) {
    rails.push_back(node_dofs(model.rails()[r]));
    for (std::size_t i = 0; i < rails[r].v.size(); ++i) {
      if (rails[r].v[i] < 0 && rails[r].rot[i] < 0)
        throw std::invalid_argument(fmt::format("rail line '{}' node {} has both DOFs fixed: it has no equation to "
                                                "label",
                                                model.rails()[r].name, i));
      for (const int d : {rails[r].v[i], rails[r].rot[i]})
        if (d >= 0) rail_ref[d] = {r, i};
    }
  }
  Labelled out;
  out.labels.resize(static_cast<std::size_t>(n));
  std::map<std::pair<std::size_t, std::size_t>, long> rail_node_label;
  long next_node = 1;
  for (int i = 0; i < n; ++i) {
    const auto ref = rail_ref.find(i);
    if (ref == rail_ref.end()) {
      out.labels[static_cast<std::size_t>(i)] = {next_node++, kVertical};
      continue;
    }
    const auto [r, k] = ref->second;
    const auto [it, fresh] = rail_node_label.try_emplace(std::make_pair(r, k), next_node);
    if (fresh) {
      ++next_node;
      out.xy[it->second] = {model.rails()[r].x_m[k], static_cast<double>(r)};
    }
    out.labels[static_cast<std::size_t>(i)] = {it->second, rails[r].v[k] == i ? kVertical : kRotation};
  }
  nlohmann::ordered_json& map = out.map;
  map["description"] = fmt::format("Written by railvsi from a '{}' model: {} DOFs ({} deck, {} track), node "
                                   "numbers made up by the export.",
                                   model.info().source, n, model.info().deck_dofs, model.info().track_dofs);
  map["nodes_csv"] = "nodes.csv";
  map["rail_lines"] = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < rails.size(); ++r) {
    std::vector<long> nodes;
    for (std::size_t k = 0; k < rails[r].v.size(); ++k) nodes.push_back(rail_node_label.at(std::make_pair(r, k)));
    map["rail_lines"].push_back({{"name", model.rails()[r].name},
                                 {"nodes", nodes},
                                 {"vertical_dof", dof_component_name(kVertical, abaqus)},
                                 {"rotation_dof", dof_component_name(kRotation, abaqus)}});
  }
  map["output_points"] = nlohmann::ordered_json::array();
  for (const OutputPoint& p : model.outputs()) {
    const DofLabel& label = out.labels[static_cast<std::size_t>(p.dof)];
    if (label.component != kVertical)
      throw std::invalid_argument(fmt::format("output point '{}' is at a rotation DOF", p.name));
    const auto [it, fresh] = out.xy.try_emplace(label.node, p.x_m, 0.0);
    if (!fresh && it->second.first != p.x_m)
      throw std::invalid_argument(fmt::format("output point '{}' at x = {} m sits on rail node x = {} m", p.name, p.x_m,
                                              it->second.first));
    map["output_points"].push_back(
        {{"name", p.name}, {"node", label.node}, {"dof", dof_component_name(kVertical, abaqus)}});
  }
  std::vector<long> track_nodes;
  for (const int d : track_dofs(model)) {
    const long node = out.labels[static_cast<std::size_t>(d)].node;
    if (track_nodes.empty() || track_nodes.back() != node) track_nodes.push_back(node);
  }
  if (!track_nodes.empty()) map["track_nodes"] = track_nodes;
  const StructureInfo& info = model.info();
  if (info.bridge_end_m > info.bridge_start_m) {
    map["bridge_start_m"] = info.bridge_start_m;
    map["bridge_end_m"] = info.bridge_end_m;
  }
  if (info.support_x_m.size() >= 2) map["supports_x_m"] = info.support_x_m;
  return out;
}

std::string nodes_csv(const Labelled& l) {
  std::string text = "node,x,y,z\n";
  for (const auto& [node, xy] : l.xy) text += fmt::format("{},{:.17g},{:.17g},0\n", node, xy.first, xy.second);
  return text;
}

}  // namespace

std::optional<ExportFormat> export_format_from_name(std::string_view name) {
  if (name == "mtx") return ExportFormat::kMatrixMarket;
  if (name == "hb") return ExportFormat::kHarwellBoeing;
  if (name == "abaqus") return ExportFormat::kAbaqus;
  return std::nullopt;
}

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
  if (const auto track = track_dofs(model); !track.empty()) map["track_dofs"] = track;
  if (info.bridge_end_m > info.bridge_start_m) {
    map["bridge_start_m"] = info.bridge_start_m;
    map["bridge_end_m"] = info.bridge_end_m;
  }
  if (info.support_x_m.size() >= 2) map["supports_x_m"] = info.support_x_m;
  return map;
}

std::vector<FileToWrite> structure_files(const StructureModel& model, ExportFormat format) {
  const std::string ext = extension(format);
  std::vector<std::pair<std::string, const SparseMatrix*>> matrices{{"K", &model.K()}, {"M", &model.M()}};
  if (model.C().nonZeros() > 0) matrices.emplace_back("C", &model.C());
  std::vector<FileToWrite> files;
  if (format == ExportFormat::kMatrixMarket) {
    const nlohmann::ordered_json map = structure_map_json(model);  // fails before anything is written
    for (const auto& [key, A] : matrices)
      files.push_back({key + ext, [A](const auto& file) { write_matrix_market(file, *A); }});
    files.push_back({"map.json", [map](const auto& file) { write_text_file(file, map.dump(1) + "\n"); }});
    return files;
  }
  auto l = std::make_shared<const Labelled>(labelled(model, format));
  for (const auto& [key, A] : matrices) {
    if (format == ExportFormat::kHarwellBoeing) {
      files.push_back({key + ext, [A](const auto& file) { write_harwell_boeing(file, *A); }});
      files.push_back({key + ".mapping", [l](const auto& file) { write_ansys_mapping(file, l->labels); }});
    } else {
      files.push_back({key + ext, [A, l](const auto& file) { write_abaqus_matrix(file, *A, l->labels); }});
    }
  }
  files.push_back({"nodes.csv", [l](const auto& file) { write_text_file(file, nodes_csv(*l)); }});
  files.push_back({"map.json", [l](const auto& file) { write_text_file(file, l->map.dump(1) + "\n"); }});
  return files;
}

nlohmann::ordered_json structure_import_json(const StructureModel& model, ExportFormat format) {
  const std::string ext = extension(format);
  nlohmann::ordered_json files = {{"K", "K" + ext}, {"M", "M" + ext}};
  if (model.C().nonZeros() > 0) files["C"] = "C" + ext;
  files["map"] = "map.json";
  return files;
}

}  // namespace railvsi

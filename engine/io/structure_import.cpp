#include "io/structure_import.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/matrix_reader.hpp"
#include "io/matrix_text.hpp"
#include "io/schema_validator.hpp"
#include "model/en1991_damping.hpp"
#include "model/rayleigh.hpp"

namespace railvsi {

using nlohmann::json;

void check_unique_names(const json& list, const std::string& path) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto name = list[i].at("name").get<std::string>();
    if (const auto [it, fresh] = seen.emplace(name, i); !fresh)
      throw InputError(child_path(child_path(path, i), "name"),
                       fmt::format("duplicate name '{}' (already used at {})", name, child_path(path, it->second)));
  }
}

namespace {

// ---- the matrices

struct ImportedMatrices {
  SparseMatrix K, M, C;
  std::map<std::string, std::string> files;  // "K" -> file name, for messages
  std::vector<DofLabel> labels;              // of K's equations, empty when no file carries them
  bool abaqus_names = false;                 // print DOFs as U2/UR3 rather than UY/ROTZ
  std::vector<std::string> notes;
};

std::string label_text(const ImportedMatrices& m, int equation) {
  if (m.labels.empty()) return fmt::format("equation {}", equation + 1);
  const DofLabel& d = m.labels[static_cast<std::size_t>(equation)];
  return fmt::format("equation {} (node {}, {})", equation + 1, d.node, dof_component_name(d.component, m.abaqus_names));
}

// A matrix whose labels differ from K's (Abaqus leaves out a DOF without
// mass from M) is renumbered into K's equations by its labels.
SparseMatrix renumber_by_labels(const MatrixFile& f, const std::vector<DofLabel>& k_labels, const std::string& file,
                                const std::string& path) {
  std::map<DofLabel, int> k_equation;
  for (std::size_t i = 0; i < k_labels.size(); ++i) k_equation.emplace(k_labels[i], static_cast<int>(i));
  std::vector<int> to_k(f.labels.size());
  for (std::size_t i = 0; i < f.labels.size(); ++i) {
    const auto it = k_equation.find(f.labels[i]);
    if (it == k_equation.end())
      throw InputError(path, fmt::format("{}: equation {} (node {}, DOF {}) is not an equation of K", file, i + 1,
                                         f.labels[i].node, f.labels[i].component));
    to_k[i] = it->second;
  }
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(f.A.nonZeros()));
  for (Eigen::Index j = 0; j < f.A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(f.A, j); it; ++it)
      t.emplace_back(to_k[static_cast<std::size_t>(it.row())], to_k[static_cast<std::size_t>(it.col())], it.value());
  const auto n = static_cast<Eigen::Index>(k_labels.size());
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

ImportedMatrices read_matrices(const json& files, const std::filesystem::path& base_dir) {
  ImportedMatrices m;
  const auto read = [&](const char* key) {
    const auto file = resolve_relative(base_dir, files.at(key).get<std::string>());
    const std::string path = child_path("/structure/import", key);
    m.files[key] = file.string();
    MatrixFile f = read_matrix_file(file, path);
    m.notes.push_back(fmt::format("{}: {} ({}, {} equations)", key, file.string(), f.format, f.A.rows()));
    if (std::string(key) == "K") {
      m.labels = std::move(f.labels);
      m.abaqus_names = f.format.starts_with("Abaqus");
    } else if (!m.labels.empty() && !f.labels.empty() && f.labels != m.labels) {
      return renumber_by_labels(f, m.labels, file.string(), path);
    }
    return std::move(f.A);
  };
  m.K = read("K");
  m.M = read("M");
  if (files.contains("C")) m.C = read("C");
  for (const auto& [key, A] : {std::pair<const char*, const SparseMatrix*>{"M", &m.M}, {"C", &m.C}})
    if (A->rows() > 0 && A->rows() != m.K.rows())
      throw InputError(child_path("/structure/import", key),
                       fmt::format("{}: {} is {} x {} but K is {} x {}; sizes must agree", m.files[key], key, A->rows(),
                                   A->cols(), m.K.rows(), m.K.cols()));
  return m;
}

// A DOF that is constrained in the package but left in the export has an
// all-zero row (and column) in K: K is singular there.
void check_no_empty_rows(const ImportedMatrices& m) {
  for (Eigen::Index j = 0; j < m.K.outerSize(); ++j) {
    bool any = false;
    for (SparseMatrix::InnerIterator it(m.K, j); it && !any; ++it) any = it.value() != 0.0;
    if (!any)
      throw InputError("/structure/import/K",
                       fmt::format("{}: {} has an all-zero row and column in K: a constrained DOF left in the "
                                   "matrix. Export the matrices with the boundary conditions applied (the "
                                   "constrained DOFs removed)",
                                   m.files.at("K"), label_text(m, static_cast<int>(j))));
  }
}

// ---- node coordinates and labels

struct NodeXyz {
  double x = 0.0, y = 0.0, z = 0.0;
  long line = 0;
};

std::map<long, NodeXyz> read_node_coordinates(const std::filesystem::path& file) {
  TextLines lines(file, "/nodes_csv");
  std::map<long, NodeXyz> nodes;
  for (std::string line; lines.next(line);) {
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::string fields = line;
    std::replace(fields.begin(), fields.end(), ',', ' ');
    std::istringstream ss(fields);
    std::string first;
    ss >> first;
    if (nodes.empty() && !first.empty() && !std::isdigit(static_cast<unsigned char>(first[0])) && first[0] != '-')
      continue;  // the heading
    long node = 0;
    NodeXyz p;
    std::string rest;
    const auto [ptr, ec] = std::from_chars(first.data(), first.data() + first.size(), node);
    if (ec != std::errc() || ptr != first.data() + first.size() || !(ss >> p.x >> p.y >> p.z) || (ss >> rest) ||
        !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw lines.error(fmt::format("expected 'node,x,y,z' (finite numbers), found '{}'", line));
    p.line = lines.number();
    if (const auto [it, fresh] = nodes.emplace(node, p); !fresh)
      throw lines.error(fmt::format("node {} is listed twice (also on line {})", node, it->second.line));
  }
  return nodes;
}

class LabelIndex {
 public:
  explicit LabelIndex(const ImportedMatrices& m) {
    for (std::size_t i = 0; i < m.labels.size(); ++i) {
      const auto [it, fresh] = by_node_.try_emplace(m.labels[i].node);
      if (fresh) it->second.fill(-1);
      it->second[static_cast<std::size_t>(m.labels[i].component)] = static_cast<int>(i);
    }
  }
  std::size_t num_nodes() const { return by_node_.size(); }
  bool has_node(long node) const { return by_node_.contains(node); }
  // The equation of (node, component), -1 when the node has no such equation.
  int equation(long node, int component) const {
    const auto it = by_node_.find(node);
    return it == by_node_.end() ? -1 : it->second[static_cast<std::size_t>(component)];
  }
  std::vector<int> equations_of(long node) const {
    std::vector<int> out;
    if (const auto it = by_node_.find(node); it != by_node_.end())
      for (const int e : it->second)
        if (e >= 0) out.push_back(e);
    return out;
  }

 private:
  std::map<long, std::array<int, 7>> by_node_;
};

// ---- the map

struct StructureMap {
  std::vector<RailLine> rails;
  std::vector<OutputPoint> outputs;
  std::vector<int> track;
  std::vector<std::string> notes, warnings;
  std::map<int, std::string> rail_dof_names;  // for the mass check's message
  double bridge_start_m = 0.0, bridge_end_m = 0.0;
  std::vector<double> supports_x_m;  // empty: not given
};

class MapReader {
 public:
  MapReader(const json& doc, const ImportedMatrices& m, std::filesystem::path map_file)
      : doc_(doc), m_(m), labels_(m), map_file_(std::move(map_file)) {}

  StructureMap read() {
    StructureMap map;
    check_unique_names(doc_.at("rail_lines"), "/rail_lines");
    for (std::size_t r = 0; r < doc_.at("rail_lines").size(); ++r)
      map.rails.push_back(rail_line(doc_.at("rail_lines")[r], child_path("/rail_lines", r), map));
    if (doc_.contains("output_points")) {
      check_unique_names(doc_.at("output_points"), "/output_points");
      for (std::size_t p = 0; p < doc_.at("output_points").size(); ++p)
        map.outputs.push_back(output_point(doc_.at("output_points")[p], child_path("/output_points", p), map));
    }
    read_track(map);
    const RailLine& first = map.rails.front();
    if (doc_.contains("supports_x_m")) {
      map.supports_x_m = doc_.at("supports_x_m").get<std::vector<double>>();
      for (std::size_t i = 0; i < map.supports_x_m.size(); ++i) {
        const double x = map.supports_x_m[i];
        const std::string at = child_path("/supports_x_m", i);
        if (!std::isfinite(x) || !first.covers(x))
          throw InputError(at, fmt::format("{} m is not on rail line '{}' ({} to {} m)", x, first.name,
                                           first.x_m.front(), first.x_m.back()));
        if (i > 0 && !(x > map.supports_x_m[i - 1]))
          throw InputError(at, fmt::format("supports must increase: {} m after {} m", x, map.supports_x_m[i - 1]));
      }
    }
    const bool supports = !map.supports_x_m.empty();
    map.bridge_start_m = doc_.value("bridge_start_m", supports ? map.supports_x_m.front() : first.x_m.front());
    map.bridge_end_m = doc_.value("bridge_end_m", supports ? map.supports_x_m.back() : first.x_m.back());
    if (!(map.bridge_end_m > map.bridge_start_m))
      throw InputError("/bridge_end_m", fmt::format("must be greater than bridge_start_m ({})", map.bridge_start_m));
    const double length_m = map.rails.front().x_m.back() - map.rails.front().x_m.front();
    if (length_m > 20e3)
      map.warnings.push_back(fmt::format("rail line '{}' is {:.0f} m long: are the coordinates in mm? railvsi works "
                                         "in SI units (m, kg, N)",
                                         map.rails.front().name, length_m));
    return map;
  }

 private:
  void require_labels(const std::string& path) const {
    if (m_.labels.empty())
      throw InputError(path, fmt::format("given by node numbers, but {} carries no node/DOF labels; give equation "
                                         "numbers (x_m, dof_v, dof_rot), or export Abaqus matrix output or "
                                         "Harwell-Boeing with its ANSYS .mapping file",
                                         m_.files.at("K")));
  }
  const NodeXyz& coordinates(long node, const std::string& path) {
    if (!nodes_) {
      if (!doc_.contains("nodes_csv"))
        throw InputError(path, "a node number needs coordinates: give nodes_csv (lines 'node,x,y,z')");
      nodes_file_ = resolve_relative(map_file_.parent_path(), doc_.at("nodes_csv").get<std::string>()).string();
      nodes_ = read_node_coordinates(nodes_file_);
    }
    const auto it = nodes_->find(node);
    if (it == nodes_->end()) throw InputError(path, fmt::format("node {} has no coordinates in {}", node, nodes_file_));
    return it->second;
  }
  int component(const json& item, const char* key, const std::string& path, bool rotation) const {
    const auto name = item.at(key).get<std::string>();
    const int c = dof_component(name);
    if (c == 0 || (c > 3) != rotation)
      throw InputError(child_path(path, key),
                       fmt::format("'{}' is not a {} DOF name ({})", name, rotation ? "rotation" : "displacement",
                                   rotation ? "UR1-UR3, ROTX-ROTZ or 4-6" : "U1-U3, UX-UZ or 1-3"));
    return c;
  }
  std::string dof_name(int c) const { return dof_component_name(c, m_.abaqus_names); }

  RailLine rail_line(const json& line, const std::string& path, StructureMap& map) {
    const auto name = line.at("name").get<std::string>();
    if (!line.contains("nodes")) {
      const auto x_m = line.at("x_m").get<std::vector<double>>();
      const auto dof_v = line.at("dof_v").get<std::vector<int>>();
      const auto dof_rot = line.at("dof_rot").get<std::vector<int>>();
      for (const char* key : {"dof_v", "dof_rot"})
        if (line.at(key).size() != x_m.size())
          throw InputError(child_path(path, key), fmt::format("has {} entries but x_m has {}: one per node",
                                                              line.at(key).size(), x_m.size()));
      for (std::size_t i = 0; i < x_m.size(); ++i) {
        if (dof_v[i] >= 0) map.rail_dof_names[dof_v[i]] = fmt::format("rail line '{}' node {} (vertical)", name, i);
        if (dof_rot[i] >= 0) map.rail_dof_names[dof_rot[i]] = fmt::format("rail line '{}' node {} (rotation)", name, i);
      }
      map.notes.push_back(fmt::format("rail line '{}': {} nodes by equation number, x {:.3f} to {:.3f} m", name,
                                      x_m.size(), x_m.front(), x_m.back()));
      return RailLine::from_nodes(name, x_m, dof_v, dof_rot);
    }
    require_labels(child_path(path, "nodes"));
    const int cv = component(line, "vertical_dof", path, false), cr = component(line, "rotation_dof", path, true);
    // The Hermite rail needs theta = +dv/dx with x along the track: with y
    // up that is the rotation about z (right hand: x turns towards y); with
    // z up the rotation about y is -dw/dx.
    if (!(cv == 2 && cr == 6))
      throw InputError(child_path(path, "rotation_dof"),
                       fmt::format("{} with {}: railvsi needs the vertical displacement along y and the rotation "
                                   "about z ({}/{}), x along the track, so that the rotation is +dv/dx; export the "
                                   "model with y up",
                                   dof_name(cv), dof_name(cr), dof_name(2), dof_name(6)));
    const auto nodes = line.at("nodes").get<std::vector<long>>();
    std::vector<double> x;
    std::vector<int> dof_v, dof_rot;
    int fixed = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string node_path = child_path(child_path(path, "nodes"), i);
      const NodeXyz& p = coordinates(nodes[i], node_path);
      if (!labels_.has_node(nodes[i]))
        throw InputError(node_path, fmt::format("rail node {} is not in the matrices: no equation of {} is labelled "
                                                "with it",
                                                nodes[i], m_.files.at("K")));
      if (i > 0 && !(p.x > x.back())) {
        const NodeXyz& before = coordinates(nodes[i - 1], node_path);
        throw InputError(node_path, fmt::format("rail nodes must be ordered along x: node {} (x = {} m, {} line {}) "
                                                "follows node {} (x = {} m, line {})",
                                                nodes[i], p.x, nodes_file_, p.line, nodes[i - 1], before.x,
                                                before.line));
      }
      x.push_back(p.x);
      dof_v.push_back(labels_.equation(nodes[i], cv));
      dof_rot.push_back(labels_.equation(nodes[i], cr));
      fixed += (dof_v.back() < 0) + (dof_rot.back() < 0);
      for (const auto& [d, c] : {std::pair{dof_v.back(), cv}, std::pair{dof_rot.back(), cr}})
        if (d >= 0) map.rail_dof_names[d] = fmt::format("rail line '{}' node {} {}", name, nodes[i], dof_name(c));
    }
    map.notes.push_back(fmt::format("rail line '{}': {} nodes {} ... {} by {}/{}, x {:.3f} to {:.3f} m from {} "
                                    "(increasing); {} of their DOFs fixed (not in the matrices)",
                                    name, nodes.size(), nodes.front(), nodes.back(), dof_name(cv), dof_name(cr),
                                    x.front(), x.back(), nodes_file_, fixed));
    return RailLine::from_nodes(name, x, dof_v, dof_rot);
  }

  OutputPoint output_point(const json& p, const std::string& path, StructureMap& map) {
    const auto name = p.at("name").get<std::string>();
    if (!p.contains("node")) return {name, p.at("x_m").get<double>(), p.at("dof").get<int>()};
    require_labels(child_path(path, "node"));
    const long node = p.at("node").get<long>();
    const int c = component(p, "dof", path, false);
    const NodeXyz& xyz = coordinates(node, child_path(path, "node"));
    const int dof = labels_.equation(node, c);
    if (dof < 0)
      throw InputError(child_path(path, "node"),
                       fmt::format("node {} has no {} equation in {}{}", node, dof_name(c), m_.files.at("K"),
                                   labels_.has_node(node) ? " (fixed there?)" : " (the node is not in the matrices)"));
    map.notes.push_back(fmt::format("output point '{}': node {} {} = equation {}, x = {:.3f} m", name, node,
                                    dof_name(c), dof + 1, xyz.x));
    return {name, xyz.x, dof};
  }

  void read_track(StructureMap& map) const {
    const int n = static_cast<int>(m_.K.rows());
    if (doc_.contains("track_nodes")) {
      require_labels("/track_nodes");
      const auto nodes = doc_.at("track_nodes").get<std::vector<long>>();
      for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!labels_.has_node(nodes[i]))
          throw InputError(child_path("/track_nodes", i),
                           fmt::format("track node {} is not in the matrices: no equation of {} is labelled with it",
                                       nodes[i], m_.files.at("K")));
        for (const int e : labels_.equations_of(nodes[i])) map.track.push_back(e);
      }
    }
    if (doc_.contains("track_dofs")) {
      const auto dofs = doc_.at("track_dofs").get<std::vector<int>>();
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        if (dofs[i] >= n)
          throw InputError(child_path("/track_dofs", i), fmt::format("equation {} outside the model (0..{})", dofs[i], n - 1));
        map.track.push_back(dofs[i]);
      }
    }
    std::sort(map.track.begin(), map.track.end());
    map.track.erase(std::unique(map.track.begin(), map.track.end()), map.track.end());
    if (!map.track.empty())
      map.notes.push_back(fmt::format("track: {} DOFs from the map's {}; deck: the other {}", map.track.size(),
                                      doc_.contains("track_nodes") ? "track_nodes" : "track_dofs",
                                      n - static_cast<int>(map.track.size())));
  }

  const json& doc_;
  const ImportedMatrices& m_;
  LabelIndex labels_;
  std::filesystem::path map_file_;
  std::optional<std::map<long, NodeXyz>> nodes_;
  std::string nodes_file_;
};

// The wheels load the rail DOFs: M must be positive definite there, or a
// rail node has no inertia (a massless DOF a wheel would excite without
// limit). LDL^T in the rail DOFs' own order names the first failing one.
void check_rail_mass(const StructureModel& model, const ImportedMatrices& m, const StructureMap& map) {
  const std::vector<int>& dofs = model.rail_dofs();
  std::vector<int> position(static_cast<std::size_t>(model.num_dofs()), -1);
  for (std::size_t k = 0; k < dofs.size(); ++k) position[static_cast<std::size_t>(dofs[k])] = static_cast<int>(k);
  std::vector<Triplet> block;
  for (const int j : dofs)
    for (SparseMatrix::InnerIterator it(model.M(), j); it; ++it)
      if (position[static_cast<std::size_t>(it.row())] >= 0)
        block.emplace_back(position[static_cast<std::size_t>(it.row())], position[static_cast<std::size_t>(j)],
                           it.value());
  const int n = static_cast<int>(dofs.size());
  SparseMatrix B(n, n);
  B.setFromTriplets(block.begin(), block.end());
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(B);
  const Vector d = ldlt.vectorD();
  for (int k = 0; k < n && k < d.size(); ++k)
    if (!(d[k] > 0.0)) {
      const int dof = dofs[static_cast<std::size_t>(k)];
      const auto where = map.rail_dof_names.find(dof);
      throw InputError("/structure/import/M",
                       fmt::format("{}: M is not positive definite on the rail DOFs: pivot {:.3e} at {}{}; every "
                                   "rail DOF needs mass (a consistent or lumped rail mass, rotational inertia "
                                   "included)",
                                   m.files.at("M"), d[k], label_text(m, dof),
                                   where == map.rail_dof_names.end() ? "" : ", " + where->second));
    }
}

// The damping ratio given, or EN 1991-2 Table 6.6's for the bridge type at
// the longest span (between the map's supports, else the bridge's length),
// as bridge-2d takes it; with where it came from.
std::pair<double, std::string> damping_ratio(const json& damping, const StructureInfo& info) {
  if (damping.contains("en1991") == damping.contains("ratio"))
    throw InputError("/structure/damping", "give exactly one of ratio (the damping ratio) and en1991 (the lower "
                                           "bound of EN 1991-2 Table 6.6 for a bridge type)");
  if (damping.contains("ratio")) return {damping.at("ratio").get<double>(), "given (Rayleigh on the whole imported model)"};
  const auto name = damping.at("en1991").at("bridge_type").get<std::string>();
  const auto type = en1991_bridge_type_from_name(name);
  if (!type) throw InputError("/structure/damping/en1991/bridge_type", fmt::format("unknown bridge type '{}'", name));
  const std::vector<double>& supports = info.support_x_m;
  double longest_m = info.bridge_end_m - info.bridge_start_m;
  if (supports.size() >= 2) {
    longest_m = 0.0;
    for (std::size_t i = 1; i < supports.size(); ++i) longest_m = std::max(longest_m, supports[i] - supports[i - 1]);
  }
  return {en1991_damping_ratio(*type, longest_m),
          fmt::format("EN 1991-2 Table 6.6, {}, L = {:g} m (longest span{}; Rayleigh on the whole imported model)",
                      name, longest_m, supports.size() >= 2 ? " between the map's supports" : ": the bridge")};
}

// C = a0 M + a1 K with the ratio matched at f1 and f2.
SparseMatrix rayleigh_damping(const ImportedMatrices& m, const json& damping, double ratio) {
  const double f1 = damping.at("f1_hz").get<double>(), f2 = damping.at("f2_hz").get<double>();
  if (!(f2 > f1)) throw InputError("/structure/damping/f2_hz", "must be greater than f1_hz");
  const RayleighCoefficients r = rayleigh_coefficients(ratio, f1, f2);
  return SparseMatrix(r.a0_per_s * m.M + r.a1_s * m.K);
}

// StructureModel reports "/structure/...": rail lines and output points are
// in the map file, matrices in the scene's import object.
InputError place_model_error(const InputError& e, const ImportedMatrices& m, const std::string& map_file) {
  const std::string& path = e.json_path();
  const std::string rest = path.substr(std::string("/structure").size());
  if (rest.starts_with("/rail_lines") || rest.starts_with("/output_points")) return InputError(rest, e.what(), map_file);
  for (const auto& [key, file] : m.files)
    if (rest == "/" + key) return InputError(child_path("/structure/import", key), fmt::format("{}: {}", file, e.what()));
  return InputError("/structure/import", e.what());
}

}  // namespace

std::shared_ptr<const StructureModel> import_structure(const json& s, const json& outputs,
                                                       const std::filesystem::path& base_dir) {
  if (outputs.contains("points"))
    throw InputError("/outputs/points", "an imported structure lists its output points in its map file");
  const json& files = s.at("import");
  if (files.contains("C") && s.contains("damping"))
    throw InputError("/structure/damping", "give either import.C or damping, not both");
  ImportedMatrices m = read_matrices(files, base_dir);
  check_no_empty_rows(m);
  if (s.contains("variant")) {  // a bound of mass and stiffness (EN 1991-2 6.4.6.3): the whole model
    const double mass_factor = s.at("variant").value("mass_factor", 1.0);
    const double EI_factor = s.at("variant").value("EI_factor", 1.0);
    m.M *= mass_factor;
    m.K *= EI_factor;
    m.notes.push_back(fmt::format("variant: M x {:g}, K x {:g}", mass_factor, EI_factor));
  }
  const auto map_file = resolve_relative(base_dir, files.at("map").get<std::string>());
  const json map_doc = read_json_file(map_file);
  StructureMap map = parse_validated(map_doc, "structure-map.schema.json", map_file.string(),
                                     [&] { return MapReader(map_doc, m, map_file).read(); });
  StructureInfo info;
  info.source = "import";
  info.bridge_start_m = map.bridge_start_m;
  info.bridge_end_m = map.bridge_end_m;
  info.support_x_m = std::move(map.supports_x_m);
  info.track_dof_list = std::move(map.track);
  info.track_dofs = static_cast<int>(info.track_dof_list.size());
  info.deck_dofs = static_cast<int>(m.K.rows()) - info.track_dofs;
  if (s.contains("damping")) {
    const auto [ratio, source] = damping_ratio(s.at("damping"), info);
    info.damping_ratio = ratio;
    info.damping_source = source;
    m.C = rayleigh_damping(m, s.at("damping"), ratio);
  } else {
    info.damping_source = files.contains("C") ? "imported C matrix" : "none";
    if (!files.contains("C")) info.damping_ratio = 0.0;
  }
  info.import_notes = m.notes;
  if (!m.labels.empty()) {
    info.import_notes.push_back(fmt::format("labels: {} equations on {} nodes", m.labels.size(),
                                            LabelIndex(m).num_nodes()));
  }
  info.import_notes.insert(info.import_notes.end(), map.notes.begin(), map.notes.end());
  info.import_warnings = map.warnings;
  std::shared_ptr<const StructureModel> model;
  try {
    model = std::make_shared<const StructureModel>(m.K, m.M, m.C, std::move(map.rails), std::move(map.outputs),
                                                   std::move(info));
  } catch (const InputError& e) {
    throw place_model_error(e, m, map_file.string());
  }
  check_rail_mass(*model, m, map);
  return model;
}

}  // namespace railvsi

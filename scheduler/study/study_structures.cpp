#include "study/study_structures.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/schema_validator.hpp"

namespace railvsi::scheduler {
namespace {

using nlohmann::json;

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, separator)) fields.push_back(trimmed(field));
  if (!line.empty() && line.back() == separator) fields.emplace_back();
  return fields;
}

// "20", "15 20 15" or "15;20;15": finite numbers, at least one.
bool parse_numbers(const std::string& text, std::vector<double>& out) {
  std::string spaced = text;
  for (char& c : spaced)
    if (c == ';') c = ' ';
  std::istringstream in(spaced);
  std::string token;
  while (in >> token) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(token, &used);
    } catch (const std::exception&) {
      return false;
    }
    if (used != token.size() || !std::isfinite(value)) return false;
    out.push_back(value);
  }
  return !out.empty();
}

const std::set<std::string>& damping_rules() {
  static const std::set<std::string> types = {"steel-composite", "prestressed-concrete", "reinforced-concrete",
                                              "filler-beam"};
  return types;
}

}  // namespace

std::vector<NamedStructure> read_structures_csv(const std::filesystem::path& csv, const std::string& path,
                                                const std::string& file) {
  std::ifstream in(csv);
  if (!in) throw InputError(path, fmt::format("cannot read the structures CSV {}", csv.string()), file);
  const auto error = [&](int line, const std::string& what) {
    return InputError(path, line > 0 ? fmt::format("{}:{}: {}", csv.string(), line, what)
                                     : fmt::format("{}: {}", csv.string(), what),
                      file);
  };
  static const std::vector<std::string> required = {"name", "spans_m", "EI_Nm2", "mass_kg_per_m", "damping"};
  static const std::set<std::string> known = {"name",    "spans_m",         "EI_Nm2",    "mass_kg_per_m",
                                              "damping", "output_points_m", "continuous"};
  std::map<std::string, std::size_t> column;
  std::vector<NamedStructure> out;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::string text = trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    const std::vector<std::string> fields = split(text, ',');
    if (column.empty()) {
      for (std::size_t k = 0; k < fields.size(); ++k) {
        if (!known.count(fields[k]))
          throw error(number, fmt::format("unknown column '{}' in the header; the columns are name, spans_m, EI_Nm2, "
                                          "mass_kg_per_m, damping and optionally output_points_m, continuous",
                                          fields[k]));
        if (!column.emplace(fields[k], k).second)
          throw error(number, fmt::format("column '{}' appears twice in the header", fields[k]));
      }
      for (const std::string& c : required)
        if (!column.count(c)) throw error(number, fmt::format("the header has no column '{}'", c));
      continue;
    }
    if (fields.size() != column.size())
      throw error(number, fmt::format("{} fields, the header names {}", fields.size(), column.size()));
    const auto field = [&](const char* name) -> const std::string& { return fields[column.at(name)]; };
    const auto number_list = [&](const char* name) {
      std::vector<double> values;
      if (!parse_numbers(field(name), values))
        throw error(number, fmt::format("{}: expected numbers separated by spaces or ';', found '{}'", name, field(name)));
      return values;
    };
    const auto one_number = [&](const char* name) {
      const std::vector<double> values = number_list(name);
      if (values.size() != 1) throw error(number, fmt::format("{}: expected one number, found '{}'", name, field(name)));
      return values.front();
    };
    NamedStructure s;
    s.name = field("name");
    if (s.name.empty()) throw error(number, "name: empty; every bridge needs a name");
    s.path = path;
    s.origin = fmt::format("{}:{}", csv.string(), number);
    json damping;
    const std::string& d = field("damping");
    if (damping_rules().count(d)) {
      damping = {{"en1991", {{"bridge_type", d}}}};
    } else {
      std::vector<double> ratio;
      if (!parse_numbers(d, ratio) || ratio.size() != 1)
        throw error(number, fmt::format("damping: expected a ratio (e.g. 0.02) or a bridge type of EN 1991-2 Table "
                                        "6.6 (steel-composite, prestressed-concrete, reinforced-concrete, "
                                        "filler-beam), found '{}'", d));
      damping = {{"ratio", ratio.front()}};
    }
    s.structure = {{"generator", "bridge-2d"},
                   {"spans_m", number_list("spans_m")},
                   {"deck", {{"EI_Nm2", one_number("EI_Nm2")}, {"mass_kg_per_m", one_number("mass_kg_per_m")}}},
                   {"damping", damping},
                   {"track", nullptr}};
    if (column.count("continuous") && !field("continuous").empty()) {
      const std::string& c = field("continuous");
      if (c != "true" && c != "false")
        throw error(number, fmt::format("continuous: expected true or false, found '{}'", c));
      s.structure["continuous"] = c == "true";
    }
    try {
      shared_schema_validator("structure.schema.json").validate(s.structure, csv.string());
    } catch (const InputError& e) {
      throw error(number, fmt::format("bridge '{}': {}: {}", s.name, e.json_path(), e.what()));
    }
    if (column.count("output_points_m") && !field("output_points_m").empty()) {
      json points = json::array();
      for (double x : number_list("output_points_m"))
        points.push_back({{"name", fmt::format("x={:g}", x)}, {"x_m", x}});
      s.outputs = {{"points", points}};
    }
    out.push_back(std::move(s));
  }
  if (column.empty()) throw error(0, "empty; expected a header line and one line per bridge");
  if (out.empty()) throw error(0, "no bridge; expected one line per bridge after the header");
  return out;
}

std::vector<NamedStructure> study_structures(const json& study, const std::filesystem::path& base_dir,
                                             const std::string& file) {
  const bool one = study.contains("structure"), many = study.contains("structures");
  if (one && many) throw InputError("/structures", "give structure or structures, not both", file);
  if (!one && !many) throw InputError("/structure", "give the structure (structure) or a line of them (structures)", file);
  if (one) return {{"", study.at("structure"), nullptr, "/structure", ""}};
  const json& list = study.at("structures");
  std::vector<NamedStructure> out;
  if (list.is_object()) {
    out = read_structures_csv(resolve_relative(base_dir, list.at("csv").get<std::string>()), "/structures/csv", file);
  } else {
    for (std::size_t k = 0; k < list.size(); ++k) {
      const json& item = list[k];
      const std::string path = child_path("/structures", k);
      out.push_back({item.at("name").get<std::string>(), item.at("structure"),
                     item.contains("outputs") ? item.at("outputs") : json(nullptr), path + "/structure", ""});
    }
  }
  std::map<std::string, std::size_t> seen;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const NamedStructure& s = out[k];
    const std::string where = s.origin.empty() ? child_path("/structures", k) + "/name" : s.path;
    if (const auto [it, fresh] = seen.emplace(s.name, k); !fresh)
      throw InputError(where, fmt::format("{}the name '{}' is given to two structures (the {} and the {}): names identify "
                                          "the bridges of a line",
                                          s.origin.empty() ? "" : s.origin + ": ", s.name, it->second + 1, k + 1),
                       file);
    if (study.contains("variants") && s.structure.contains("variant"))
      throw InputError(s.origin.empty() ? s.path + "/variant" : s.path,
                       "give the bounds of the structure in the study's variants, not both", file);
  }
  return out;
}

}  // namespace railvsi::scheduler

#include "io/irregularity_loader.hpp"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/track_defect.hpp"
#include "generators/track_spectrum.hpp"
#include "io/input_file.hpp"
#include "io/json_document.hpp"
#include "io/schema_validator.hpp"
#include "io/text_fields.hpp"

namespace railvsi {
namespace {

struct ProfileSamples {
  std::vector<double> x_m, r_m;
  std::vector<int> line;  // line of each sample, for errors found later
};

InputError csv_error(const std::filesystem::path& file, int line, const std::string& what) {
  return InputError("/csv", line > 0 ? fmt::format("{}:{}: {}", file.string(), line, what)
                                     : fmt::format("{}: {}", file.string(), what));
}

bool is_blank_or_comment(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

// A header names the columns; a line starting with a digit is a bad sample.
bool looks_like_header(const std::string& line) {
  const auto first = line.find_first_not_of(" \t");
  return std::isalpha(static_cast<unsigned char>(line[first])) || line[first] == '"';
}

// Two columns x_m, r_m separated by a comma, a semicolon or blanks; one
// header line allowed before the first sample; '#' starts a comment line.
ProfileSamples read_profile_csv(const std::filesystem::path& file) {
  if (std::filesystem::exists(file)) {
    try {
      check_input_file(file, kMaxTableFileBytes);
    } catch (const InputError& e) {
      throw csv_error(file, 0, e.what());
    }
  }
  std::ifstream in(file);
  if (!in) throw csv_error(file, 0, "cannot open the profile file");
  ProfileSamples s;
  bool header_allowed = true;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (is_blank_or_comment(line)) continue;
    std::string fields = line;
    std::replace_if(fields.begin(), fields.end(), [](char c) { return c == ',' || c == ';'; }, ' ');
    double x = 0.0, r = 0.0;
    if (parse_fields(fields, x, r)) {
      // The schema's bound of an inline r_m: a profile is millimetres.
      if (!(std::abs(r) <= 1.0))
        throw csv_error(file, number, fmt::format("r_m = {:g} m: a rail profile value must lie in [-1, 1] m "
                                                  "(is the file in millimetres?)", r));
      s.x_m.push_back(x);
      s.r_m.push_back(r);
      s.line.push_back(number);
    } else if (!header_allowed || !looks_like_header(line)) {
      throw csv_error(file, number, fmt::format("expected two numbers 'x_m, r_m', found '{}'", line));
    }
    header_allowed = false;
  }
  if (s.x_m.empty()) throw csv_error(file, 0, "no samples; expected lines 'x_m, r_m' (one header line allowed)");
  return s;
}

// Index k of a path ".../k" reported by the Irregularity constructor.
std::optional<std::size_t> trailing_index(const std::string& json_path) {
  const std::string last = json_path.substr(json_path.rfind('/') + 1);
  if (last.empty() || !std::all_of(last.begin(), last.end(), [](unsigned char c) { return std::isdigit(c); })) return std::nullopt;
  return std::stoul(last);
}

std::shared_ptr<const Irregularity> irregularity_from_csv(const std::filesystem::path& file) {
  ProfileSamples s = read_profile_csv(file);
  const std::vector<int> lines = s.line;
  try {
    return std::make_shared<const Irregularity>(std::move(s.x_m), std::move(s.r_m), file.string());
  } catch (const InputError& e) {
    const auto k = trailing_index(e.json_path());
    throw csv_error(file, k && *k < lines.size() ? lines[*k] : 0, e.what());
  }
}

// The one base profile of the node ("csv", "x_m" or "spectrum"), if any.
std::optional<std::string> base_key(const nlohmann::json& node) {
  std::optional<std::string> key;
  for (const char* k : {"csv", "x_m", "spectrum"}) {
    if (!node.contains(k)) continue;
    if (key) throw InputError("/" + std::string(k), fmt::format("give one profile: {} or {}, not both", *key, k));
    key = k;
  }
  return key;
}

std::vector<TrackDefect> parse_defects(const nlohmann::json& node) {
  std::vector<TrackDefect> defects;
  for (const auto& d : node.value("defects", nlohmann::json::array()))
    defects.push_back({d.at("type").get<std::string>() == "bump" ? DefectShape::kBump : DefectShape::kDip,
                       d.at("x_m").get<double>(), d.at("length_m").get<double>(), d.at("depth_m").get<double>()});
  return defects;
}

SpectrumSampling parse_sampling(const nlohmann::json& node) {
  SpectrumSampling s;
  s.seed = node.at("seed").get<std::uint64_t>();
  s.wavelength_min_m = node.value("wavelength_min_m", s.wavelength_min_m);
  s.wavelength_max_m = node.value("wavelength_max_m", s.wavelength_max_m);
  s.components = node.value("components", s.components);
  if (node.contains("sample_spacing_m")) s.sample_spacing_m = node.at("sample_spacing_m").get<double>();
  return s;
}

// The track, and every defect on it.
TrackRange covering(TrackRange track, const std::vector<TrackDefect>& defects) {
  for (const TrackDefect& d : defects) {
    track.start_m = std::min(track.start_m, d.x_m);
    track.end_m = std::max(track.end_m, d.x_m + d.length_m);
  }
  return track;
}

std::shared_ptr<const Irregularity> base_profile(const nlohmann::json& node, const std::string& key,
                                                 const std::filesystem::path& base_dir, TrackRange track) {
  if (key == "csv") return irregularity_from_csv(resolve_relative(base_dir, node.at("csv").get<std::string>()));
  if (key == "x_m")
    return std::make_shared<const Irregularity>(node.at("x_m").get<std::vector<double>>(),
                                                node.at("r_m").get<std::vector<double>>(), "inline");
  const std::string name = node.at("spectrum").get<std::string>();
  const TrackSpectrum* spectrum = find_track_spectrum(name);
  if (!spectrum) throw InputError("/spectrum", fmt::format("unknown spectrum '{}'", name));
  return std::make_shared<const Irregularity>(spectrum_profile(*spectrum, parse_sampling(node), track));
}

}  // namespace

std::shared_ptr<const Irregularity> parse_irregularity(const nlohmann::json& node,
                                                       const std::filesystem::path& base_dir, TrackRange track) {
  const std::optional<std::string> key = base_key(node);
  const std::vector<TrackDefect> defects = parse_defects(node);
  const auto base = key ? base_profile(node, *key, base_dir, covering(track, defects)) : nullptr;
  if (defects.empty()) {
    if (!base) throw InputError("/", "give a profile (csv, x_m and r_m, or spectrum) or defects");
    return base;
  }
  return std::make_shared<const Irregularity>(with_defects(base.get(), defects));
}

std::shared_ptr<const Irregularity> parse_irregularity_document(const nlohmann::json& doc,
                                                                const std::filesystem::path& file) {
  return parse_validated(doc, "irregularity.schema.json", file.string(),
                         [&] { return parse_irregularity(doc, file.parent_path(), kStandaloneProfileRange); });
}

}  // namespace railvsi

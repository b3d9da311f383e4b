#pragma once
// The structures of a study: its one "structure", or its "structures" (a
// line of bridges) as a fourth dimension beside trains x speeds x profiles.
// "structures" is a list of {"name", "structure", "outputs"?} or
// {"csv": FILE}, a table with one bridge-2d bridge per line (columns name,
// spans_m, EI_Nm2, mass_kg_per_m, damping, and optionally output_points_m
// and continuous). A bridge's scene is what a one-structure study of it
// would make, so that its jobs are the same jobs (the same ids): a bridge
// that two lines share is computed once.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

struct NamedStructure {
  std::string name;  // empty for a study's one "structure"
  nlohmann::json structure;                  // as a scene's structure
  nlohmann::json outputs = nullptr;          // its scene's outputs; null: the study's (or none)
  std::string path;                          // where its errors are reported in the study
  std::string origin;                        // CSV line ("line.csv:4") for errors, else empty
};

// One entry for "structure"; the list or the CSV for "structures".
// InputError naming the study file and the JSON path (or the CSV file and
// line, at /structures/csv) when both or neither are given, names repeat,
// or a CSV line is not a bridge. File names in a CSV are relative to
// base_dir.
std::vector<NamedStructure> study_structures(const nlohmann::json& study, const std::filesystem::path& base_dir,
                                             const std::string& file);

// Reads a line's bridges from a CSV file (see above); `path` is the JSON
// path of the file's name in the study, `file` the study.
std::vector<NamedStructure> read_structures_csv(const std::filesystem::path& csv, const std::string& path,
                                                const std::string& file);

}  // namespace railvsi::scheduler

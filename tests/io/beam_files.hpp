#pragma once
// The small beam of write_beam_files.py, written once per test program by
// SciPy (mmwrite, hb_write) and by the script from the documented layouts
// (Harwell-Boeing elemental, Abaqus matrix input, ANSYS mapping), and the
// same beam from the bridge-2d generator.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "generators/bridge_2d.hpp"

namespace railvsi::test {

constexpr double kBeamSpan_m = 20.0, kBeamEI_Nm2 = 5.0e9, kBeamMass_kg_per_m = 8000.0;
constexpr int kBeamElements = 10;

// The directory of the files: the one ctest's fixture test io_beam_files
// writes (RAILVSI_BEAM_FILES, read only) when it is there; else written on
// first use. Empty (and the test failed) when the script could not run.
inline const std::filesystem::path& beam_files_dir() {
  static const std::filesystem::path dir = [] {
    if (std::filesystem::is_regular_file(std::filesystem::path(RAILVSI_BEAM_FILES) / "map_index.json"))
      return std::filesystem::path(RAILVSI_BEAM_FILES);
    const auto d = std::filesystem::temp_directory_path() / ("railvsi-beam-files-" + std::to_string(::getpid()));
    std::filesystem::remove_all(d);
    const std::string command = std::string(RAILVSI_PYTHON) + " " + RAILVSI_BEAM_SCRIPT + " '" + d.string() + "' " +
                                std::to_string(kBeamSpan_m) + " " + std::to_string(kBeamElements) + " " +
                                std::to_string(kBeamEI_Nm2) + " " + std::to_string(kBeamMass_kg_per_m);
    if (std::system(command.c_str()) != 0) return std::filesystem::path();
    std::atexit([] { std::filesystem::remove_all(beam_files_dir()); });
    return d;
  }();
  return dir;
}

// Copies the beam files into `dir`, for a test that edits or adds files beside them.
inline void copy_beam_files(const std::filesystem::path& dir) {
  ASSERT_FALSE(beam_files_dir().empty()) << "write_beam_files.py failed (python3-scipy?)";
  for (const auto& entry : std::filesystem::directory_iterator(beam_files_dir()))
    std::filesystem::copy_file(entry.path(), dir / entry.path().filename());
}

// The same beam from the generator: 10 elements of 2 m, pinned ends.
inline std::shared_ptr<const StructureModel> generated_beam() {
  Bridge2dOptions o;
  o.spans_m = {kBeamSpan_m};
  o.deck_EI_Nm2 = kBeamEI_Nm2;
  o.deck_mass_kg_per_m = kBeamMass_kg_per_m;
  o.damping_ratio = 0.0;
  o.element_length_m = kBeamSpan_m / kBeamElements;
  return make_bridge_2d(o);
}

}  // namespace railvsi::test

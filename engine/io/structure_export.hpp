#pragma once
// A structure built in memory as the files of the import path (README,
// "Bringing your own FE model"), in one of the matrix formats railvsi reads,
// so that another run, or another program, can read it back with
// {"import": {...}}:
// - Matrix Market: K.mtx, M.mtx, C.mtx and map.json by equation number;
// - Harwell-Boeing: K.rsa, M.rsa, C.rsa, each with its ANSYS-style .mapping
//   file (equation, node, DOF label), map.json by node and DOF name, nodes.csv;
// - Abaqus: K.abq, M.abq, C.abq ("node, DOF, node, DOF, value" lines),
//   map.json by node and DOF name, nodes.csv.
// C is left out when it has no entries. The node numbers of the labelled
// formats are made up here (a generated model has DOFs, not nodes): a rail
// node's vertical and rotation DOFs share a node (U2/UY and UR3/ROTZ), every
// other equation is a node of its own (U2/UY). The three read back to the
// same matrices, equations and map.
#include <optional>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/file_set_writer.hpp"
#include "io/matrix_reader.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

enum class ExportFormat { kMatrixMarket, kHarwellBoeing, kAbaqus };

// "mtx", "hb", "abaqus" (command-line names); nullopt for anything else.
std::optional<ExportFormat> export_format_from_name(std::string_view name);

// The map document by equation number: rail lines node by node, output
// points, track DOFs, bridge extent. Throws std::invalid_argument when a rail
// line has different DOFs on either side of a node (the map has one pair per
// node), e.g. bridge-2d's deck line over simply supported spans.
nlohmann::ordered_json structure_map_json(const StructureModel& model);

// The files, for write_files_together. The returned writers refer to
// `model`, which must outlive them. Throws std::invalid_argument when the
// model cannot be written so (see structure_map_json; a rail node with both
// DOFs fixed has no label).
std::vector<FileToWrite> structure_files(const StructureModel& model, ExportFormat format = ExportFormat::kMatrixMarket);

// The "import" object of a scene naming those files.
nlohmann::ordered_json structure_import_json(const StructureModel& model,
                                             ExportFormat format = ExportFormat::kMatrixMarket);

}  // namespace railvsi

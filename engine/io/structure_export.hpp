#pragma once
// A structure built in memory as the files of the import path (README,
// "Scenes"): K.mtx, M.mtx, C.mtx (when C has entries) and map.json
// (schemas/structure-map.schema.json), so that another run, or another
// program, can read it back with {"import": {...}}.
#include <vector>

#include <nlohmann/json.hpp>

#include "io/file_set_writer.hpp"
#include "model/structure_model.hpp"

namespace railvsi {

// The map document: rail lines node by node, output points, bridge extent.
// Throws std::invalid_argument when a rail line has different DOFs on either
// side of a node (the map has one pair per node), e.g. bridge-2d's deck line
// over simply supported spans.
nlohmann::ordered_json structure_map_json(const StructureModel& model);

// The files, for write_files_together; "C" is left out when C is empty.
// The returned writers refer to `model`, which must outlive them.
std::vector<FileToWrite> structure_files(const StructureModel& model);

// The "import" object of a scene naming those files.
nlohmann::ordered_json structure_import_json(const StructureModel& model);

}  // namespace railvsi

#include "io/imported_structures.hpp"

#include "io/structure_import.hpp"

namespace railvsi {

std::shared_ptr<const StructureModel> ImportedStructures::import(const nlohmann::json& structure,
                                                                 const nlohmann::json& outputs,
                                                                 const std::filesystem::path& base_dir) {
  // Each part dumped whole: a key is never the same for different inputs.
  std::string key = structure.dump();
  key += '\n';
  key += outputs.dump();
  key += '\n';
  key += base_dir.string();
  auto it = read_.find(key);
  if (it != read_.end()) return it->second;
  auto model = import_structure(structure, outputs, base_dir);
  ++reads_;
  return read_.emplace(std::move(key), std::move(model)).first->second;
}

}  // namespace railvsi

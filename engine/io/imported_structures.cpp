#include "io/imported_structures.hpp"

#include "io/structure_import.hpp"

namespace railvsi {

std::shared_ptr<const StructureModel> ImportedStructures::import(const nlohmann::json& structure,
                                                                 const nlohmann::json& outputs,
                                                                 const std::filesystem::path& base_dir,
                                                                 const std::string& content_key) {
  // Each part whole, one per line (a dump has no raw newline): a key is
  // never the same for different inputs.
  std::string key = structure.dump();
  key += '\n';
  key += outputs.dump();
  key += '\n';
  key += content_key;
  key += '\n';
  key += base_dir.string();
  auto it = read_.find(key);
  if (it != read_.end()) return it->second;
  auto model = import_structure(structure, outputs, base_dir);
  ++reads_;
  if (max_models_ == 0) return model;
  while (read_.size() >= max_models_) {
    read_.erase(order_.front());
    order_.pop_front();
  }
  order_.push_back(key);
  return read_.emplace(std::move(key), std::move(model)).first->second;
}

}  // namespace railvsi

#pragma once
// The imported structures one caller has read, each by what names it: the
// scene's /structure and /outputs values and the folder their file names
// are relative to. A study reads a model once for all its trains instead
// of once per train: the files of a 25,000-DOF deck took 0.7 s a read,
// 64 % of the submission of a study of ten trains. One per caller (a
// study's expansion, its cost estimate); not shared between threads.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "model/structure_model.hpp"

namespace railvsi {

class ImportedStructures {
 public:
  // As import_structure (the same errors, on every call that reads).
  std::shared_ptr<const StructureModel> import(const nlohmann::json& structure, const nlohmann::json& outputs,
                                               const std::filesystem::path& base_dir);
  int reads() const { return reads_; }

 private:
  std::map<std::string, std::shared_ptr<const StructureModel>> read_;
  int reads_ = 0;
};

}  // namespace railvsi

#pragma once
// The imported structures one caller has read, each by what names it: the
// scene's /structure and /outputs values and the folder their file names
// are relative to. A study reads a model once for all its trains instead
// of once per train: the files of a 25,000-DOF deck took 0.7 s a read,
// 64 % of the submission of a study of ten trains. One per caller (a
// study's expansion, its cost estimate, a worker thread); not shared
// between threads.
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "model/structure_model.hpp"

namespace railvsi {

class ImportedStructures {
 public:
  // Keeps at most max_models (the oldest goes first).
  explicit ImportedStructures(std::size_t max_models = SIZE_MAX) : max_models_(max_models) {}
  // As import_structure (the same errors, on every call that reads).
  // content_key, when given, names what the caller knows of the files'
  // content (a worker: its job's operator key, which hashes the matrices
  // read at submission): a model is shared only between calls that give
  // the same one, so a long-lived worker reads again for a new study.
  std::shared_ptr<const StructureModel> import(const nlohmann::json& structure, const nlohmann::json& outputs,
                                               const std::filesystem::path& base_dir,
                                               const std::string& content_key = "");
  int reads() const { return reads_; }

 private:
  std::size_t max_models_;
  std::map<std::string, std::shared_ptr<const StructureModel>> read_;
  std::deque<std::string> order_;  // keys, oldest first
  int reads_ = 0;
};

}  // namespace railvsi

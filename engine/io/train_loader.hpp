#pragma once
// Trains from JSON: the library (jobs/trains/<name>.json), inline train
// objects (moving forces or multibody cars), and train documents.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/train.hpp"

namespace railvsi {

// <library>/trains, library = $RAILVSI_LIBRARY or the jobs/ folder of the
// source tree.
std::filesystem::path train_library_dir();
std::vector<std::string> library_train_names();

// A train of the library by name. Unknown name: InputError at "" (the
// caller's path) listing the available names; errors inside the library file
// name that file.
Train load_library_train(const std::string& name);

// A validated train object; InputError paths relative to it.
Train parse_train(const nlohmann::json& train);

// A train document of its own (schema train.schema.json), already read from `file`.
Train parse_train_document(const nlohmann::json& doc, const std::filesystem::path& file);

}  // namespace railvsi

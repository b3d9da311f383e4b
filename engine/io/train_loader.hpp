#pragma once
// Trains from JSON: the library (jobs/trains/<name>.json), inline train
// objects (moving forces, HSLM-A, or multibody vehicles), and train documents.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/train.hpp"

namespace railvsi {

// <library>/trains: library = $RAILVSI_LIBRARY when set; else, for an
// installed binary, <prefix>/share/railvsi beside <prefix>/bin (found from
// /proc/self/exe); else the jobs/ folder of the source tree (build tree).
std::filesystem::path train_library_dir();
std::vector<std::string> library_train_names();

// The names of the *.json files of `dir` without the extension, sorted
// (none if it cannot be listed).
std::vector<std::string> json_file_names(const std::filesystem::path& dir);
// A name of the library is one file name, never a path: no separator, not
// "." or "..".
bool is_plain_file_name(const std::string& name);

// A train of the library by name. Unknown name: InputError at "" (the
// caller's path) listing the available names; errors inside the library file
// name that file.
Train load_library_train(const std::string& name);

// What a scene (or a study) gives as its train, already validated: a library
// name, a library reference {"library": name, "as": ...}, or a train object.
// InputError paths relative to it. "as" overrides how a library train of
// vehicles is simulated; "multibody" for a train of moving forces is an
// InputError at "/as".
Train parse_train_reference(const nlohmann::json& train);

// A validated train object; InputError paths relative to it.
Train parse_train(const nlohmann::json& train);

// A train document of its own (schema train.schema.json), already read from `file`.
Train parse_train_document(const nlohmann::json& doc, const std::filesystem::path& file);

}  // namespace railvsi

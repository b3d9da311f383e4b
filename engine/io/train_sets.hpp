#pragma once
// Named sets of library trains (<library>/trains/sets/<name>.json, schema
// train-set.schema.json): a study lists "set:<name>" among its trains and
// the set's trains take its place.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace railvsi {

std::vector<std::string> library_train_set_names();

// The trains of a set (library names or {"library", "as"} references), in
// order. Unknown name: InputError at "" listing the sets; errors inside the
// set file name that file.
nlohmann::json load_train_set(const std::string& name);

// A study's "trains" with every "set:<name>" item replaced by the set's
// trains. An unknown set is an InputError at /trains/<i> of `file`. When
// `paths` is given, it receives each train's place in the study
// (/trains/<i>, the set's for a train of a set), for the errors found later.
nlohmann::json expand_train_sets(const nlohmann::json& trains, const std::string& file,
                                 std::vector<std::string>* paths = nullptr);

}  // namespace railvsi

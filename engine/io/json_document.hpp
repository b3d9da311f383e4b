#pragma once
// Reading JSON documents and placing errors in them. Every error of the
// input layer is an InputError that names the file and the JSON pointer of
// the offending value.
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"

namespace railvsi {

// Parses a JSON file; malformed JSON gives an InputError at "/" whose
// message has the line and column of the fault.
nlohmann::json read_json_file(const std::filesystem::path& file);
nlohmann::json parse_json_text(std::string_view text, const std::string& file_for_errors);

// JSON pointer of member `key` (escaped) or element `index` below `parent`.
std::string child_path(const std::string& parent, std::string_view key);
std::string child_path(const std::string& parent, std::size_t index);

// Runs build(). The engine's constructors report paths relative to the
// object they build; an InputError that names no file yet gets `prefix` put
// in front of its path. Errors of another document (with a file) pass as is.
template <class Build>
auto with_path_prefix(const std::string& prefix, Build&& build) -> decltype(build()) {
  try {
    return build();
  } catch (const InputError& e) {
    if (!e.file().empty()) throw;
    throw InputError(prefix + e.json_path(), e.what());
  }
}

// The file a document refers to (a matrix, a profile, a map), resolved from
// the directory of the referring document.
std::filesystem::path resolve_relative(const std::filesystem::path& base_dir, const std::string& name);

}  // namespace railvsi

#include "io/json_document.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace railvsi {

nlohmann::json parse_json_text(std::string_view text, const std::string& file_for_errors) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // A syntax error's message already has "line L, column C"; a number too
    // large for a double says which number. Drop nlohmann's error id.
    std::string message = e.what();
    if (const auto bracket = message.find("] "); message.starts_with("[json.exception") &&
                                                 bracket != std::string::npos)
      message.erase(0, bracket + 2);
    throw InputError("/", "malformed JSON: " + message, file_for_errors);
  }
}

nlohmann::json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("/", "cannot open the file for reading", file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_json_text(text.str(), file.string());
}

std::string child_path(const std::string& parent, std::string_view key) {
  std::string escaped;
  for (char c : key) {
    if (c == '~') escaped += "~0";
    else if (c == '/') escaped += "~1";
    else escaped += c;
  }
  return (parent == "/" ? std::string() : parent) + "/" + escaped;
}

std::string child_path(const std::string& parent, std::size_t index) {
  return child_path(parent, std::to_string(index));
}

std::filesystem::path resolve_relative(const std::filesystem::path& base_dir, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() ? p : base_dir / p;
}

}  // namespace railvsi

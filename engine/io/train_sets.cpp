#include "io/train_sets.hpp"

#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/input_error.hpp"
#include "io/json_document.hpp"
#include "io/schema_validator.hpp"
#include "io/train_loader.hpp"

namespace railvsi {
namespace {

constexpr std::string_view kSetPrefix = "set:";

std::filesystem::path train_set_dir() { return train_library_dir() / "sets"; }

}  // namespace

std::vector<std::string> library_train_set_names() { return json_file_names(train_set_dir()); }

nlohmann::json load_train_set(const std::string& name) {
  const std::filesystem::path dir = train_set_dir();
  const std::filesystem::path file = dir / (name + ".json");
  std::error_code ec;
  if (!is_plain_file_name(name) || !std::filesystem::is_regular_file(file, ec)) {
    const auto names = library_train_set_names();
    throw InputError("", fmt::format("unknown train set '{}'; the library {} has: {}", name, dir.string(),
                                     names.empty() ? std::string("no sets") : fmt::format("{}", fmt::join(names, ", "))));
  }
  const nlohmann::json doc = read_json_file(file);
  shared_schema_validator("train-set.schema.json").validate(doc, file.string());
  if (doc.at("name").get<std::string>() != name)
    throw InputError("/name", fmt::format("the set in {}.json is named '{}': name it '{}'", name,
                                          doc.at("name").get<std::string>(), name),
                     file.string());
  return doc.at("trains");
}

nlohmann::json expand_train_sets(const nlohmann::json& trains, const std::string& file,
                                 std::vector<std::string>* paths) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < trains.size(); ++i) {
    const nlohmann::json& t = trains[i];
    const std::string path = child_path("/trains", i);
    if (!t.is_string() || !t.get<std::string>().starts_with(kSetPrefix)) {
      out.push_back(t);
      if (paths != nullptr) paths->push_back(path);
      continue;
    }
    nlohmann::json members;
    try {
      members = load_train_set(t.get<std::string>().substr(kSetPrefix.size()));
    } catch (const InputError& e) {
      if (!e.file().empty()) throw;  // an error inside the set file
      throw InputError(path, e.what(), file);
    }
    for (const nlohmann::json& m : members) {
      out.push_back(m);
      if (paths != nullptr) paths->push_back(path);
    }
  }
  return out;
}

}  // namespace railvsi

#pragma once
// The canonical text of a JSON document, the input of content hashes: keys
// sorted, no whitespace, numbers normalized (an integral value is written as
// an integer whatever its spelling, -0 as 0, other numbers in the shortest
// form that reads back to the same double). Two documents that mean the same
// have the same text, so the same id.
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

nlohmann::json canonical_json(const nlohmann::json& doc);
std::string canonical_text(const nlohmann::json& doc);

// The canonical text of a number (as canonical_text writes it inside a document).
std::string canonical_number_text(double x);

// The canonical text of an object around the number at one top-level key:
// text(x) is canonical_text of the object with that key set to x, without
// rebuilding the document (a study writes thousands of scenes that differ
// in their speed alone).
class CanonicalNumberSlot {
 public:
  // Nullopt when the object's text cannot be split there unambiguously.
  static std::optional<CanonicalNumberSlot> make(nlohmann::json object, const std::string& key);
  std::string text(double x) const;

 private:
  std::string before_, after_;
};

}  // namespace railvsi::scheduler

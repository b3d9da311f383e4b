#pragma once
// The canonical text of a JSON document, the input of content hashes: keys
// sorted, no whitespace, numbers normalized (an integral value is written as
// an integer whatever its spelling, -0 as 0, other numbers in the shortest
// form that reads back to the same double). Two documents that mean the same
// have the same text, so the same id.
#include <string>

#include <nlohmann/json.hpp>

namespace railvsi::scheduler {

nlohmann::json canonical_json(const nlohmann::json& doc);
std::string canonical_text(const nlohmann::json& doc);

}  // namespace railvsi::scheduler

// One spelling per concept, the schema's: every name a scene may give for a
// load model, a structure backend or a contact law (the enums of
// analysis.schema.json) is the name the engine parses, records and prints,
// and every value the engine knows has its name in the schema.
#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "contact/contact_law.hpp"
#include "simulation/load_model.hpp"
#include "solver/structure_backend.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

json analysis_schema() {
  std::ifstream in(std::string(RAILVSI_SOURCE_DIR) + "/schemas/analysis.schema.json");
  EXPECT_TRUE(in.good());
  return json::parse(in);
}

// Every "enum" under a property named `property`, anywhere in the schema.
std::set<std::set<std::string>> enums_of(const json& j, const std::string& property) {
  std::set<std::set<std::string>> out;
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (key == property && value.is_object() && value.contains("enum"))
        out.insert(value.at("enum").get<std::set<std::string>>());
      for (const auto& e : enums_of(value, property)) out.insert(e);
    }
  } else if (j.is_array()) {
    for (const json& v : j)
      for (const auto& e : enums_of(v, property)) out.insert(e);
  }
  return out;
}

std::set<std::string> as_set(const std::vector<std::string>& names) { return {names.begin(), names.end()}; }

TEST(SchemaSpelling, EveryLoadModelOfTheSchemaIsTheEnginesOwnName) {
  const auto enums = enums_of(analysis_schema(), "model");
  ASSERT_EQ(enums.size(), 1u);  // fidelity.model
  EXPECT_EQ(*enums.begin(), as_set(load_model_names()));
  for (const std::string& name : *enums.begin()) {
    const auto parsed = parse_load_model(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_EQ(load_model_name(*parsed), name);
  }
  EXPECT_FALSE(parse_load_model("moving-forces").has_value());
}

TEST(SchemaSpelling, EveryStructureBackendOfTheSchemaIsTheEnginesOwnName) {
  const auto enums = enums_of(analysis_schema(), "structure");
  ASSERT_EQ(enums.size(), 1u);  // analysis.structure and fidelity.structure list the same names
  EXPECT_EQ(*enums.begin(), as_set(structure_backend_names()));
  for (const std::string& name : *enums.begin()) {
    const auto parsed = parse_structure_backend(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_EQ(structure_backend_name(*parsed), name);
  }
}

TEST(SchemaSpelling, EveryContactLawOfTheSchemaIsTheEnginesOwnName) {
  std::set<std::set<std::string>> enums = enums_of(analysis_schema(), "law");
  for (const auto& e : enums_of(analysis_schema(), "contact_law")) enums.insert(e);
  ASSERT_EQ(enums.size(), 1u);  // analysis.contact.law and fidelity.contact_law
  EXPECT_EQ(*enums.begin(), as_set(contact_law_names()));
}

}  // namespace
}  // namespace railvsi

// The schemas compiled into vsi: the same as schemas/*.json, self-describing,
// and safe for valijson's $ref cache.
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/embedded_schemas.hpp"
#include "io/schema_validator.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

const std::filesystem::path kSchemaDir = std::filesystem::path(RAILVSI_SOURCE_DIR) / "schemas";

TEST(SchemaFiles, EmbeddedSchemasAreTheFilesOfTheSchemasFolder) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSchemaDir))
    if (entry.path().string().ends_with(".schema.json")) ++files;
  ASSERT_EQ(embedded_schemas().size(), files) << "a schema was added without rebuilding";
  for (const EmbeddedSchema& s : embedded_schemas())
    EXPECT_EQ(s.text, read_text(kSchemaDir / s.name)) << s.name << " changed without being embedded again";
}

// valijson caches the subschemas of every file under their JSON pointer
// alone: two files defining the same name would share one subschema.
TEST(SchemaFiles, DefinitionNamesAreUniqueAcrossFiles) {
  std::map<std::string, std::string> owner;
  for (const EmbeddedSchema& s : embedded_schemas()) {
    const json doc = json::parse(s.text);
    if (!doc.contains("definitions")) continue;
    for (const auto& [name, definition] : doc["definitions"].items()) {
      const auto [it, fresh] = owner.emplace(name, std::string(s.name));
      EXPECT_TRUE(fresh) << name << " is defined in " << it->second << " and " << s.name;
    }
  }
}

// ... and a $ref to another file's root would collide with the root of the
// document being validated. (A document schema's own root may $ref its
// definition.)
void expect_refs_to_definitions(const json& node, const std::string& where) {
  if (node.is_object() && node.contains("$ref")) {
    const std::string ref = node["$ref"];
    EXPECT_NE(ref.find("#/definitions/"), std::string::npos)
        << where << ": $ref " << ref << " must name a definition (a file's root shares valijson's cache key \"\")";
  }
  if (node.is_structured())
    for (const auto& [key, child] : node.items()) expect_refs_to_definitions(child, where + "/" + key);
}

TEST(SchemaFiles, ReferencesNameDefinitionsOnly) {
  for (const EmbeddedSchema& s : embedded_schemas()) {
    json doc = json::parse(s.text);
    doc.erase("$ref");
    expect_refs_to_definitions(doc, std::string(s.name) + "#");
  }
}

void expect_described(const json& node, const json& document, const std::string& where) {
  if (node.is_object() && node.contains("properties"))
    for (const auto& [key, property] : node["properties"].items()) {
      bool described = property.contains("description");
      if (!described && property.contains("$ref")) {
        const std::string ref = property["$ref"];
        const auto hash = ref.find('#');
        const json target_doc = hash == 0 ? document : embedded_schema_json(ref.substr(0, hash));
        described = target_doc.at(json::json_pointer(ref.substr(hash + 1))).contains("description");
      }
      EXPECT_TRUE(described) << where << "/properties/" << key << " has no description";
    }
  if (node.is_structured())
    for (const auto& [key, child] : node.items()) expect_described(child, document, where + "/" + key);
}

TEST(SchemaFiles, EveryPropertyHasADescription) {
  for (const EmbeddedSchema& s : embedded_schemas()) {
    const json doc = json::parse(s.text);
    expect_described(doc, doc, std::string(s.name) + "#");
  }
}

TEST(SchemaFiles, EveryDocumentSchemaLoadsWithItsReferences) {
  for (const char* name : {"scene.schema.json", "train.schema.json", "irregularity.schema.json",
                           "structure-map.schema.json", "structure.schema.json", "analysis.schema.json",
                           "deck-section.schema.json"})
    EXPECT_NO_THROW(SchemaValidator{name}) << name;
}

}  // namespace
}  // namespace railvsi::test

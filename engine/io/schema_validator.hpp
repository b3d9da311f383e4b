#pragma once
// JSON Schema (draft-07) validation of input documents against the schemas
// compiled into the library (io/embedded_schemas.hpp), with valijson. $refs
// between our schema files ("train.schema.json#/definitions/train") are
// resolved among the embedded schemas; nothing is read from disk.
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"

namespace railvsi {

// The parsed embedded schema of that file name. Throws std::logic_error when
// there is none (a build problem, not an input problem).
nlohmann::json embedded_schema_json(std::string_view schema_name);

class SchemaValidator {
 public:
  // schema_name: a file of schemas/, e.g. "scene.schema.json".
  explicit SchemaValidator(std::string_view schema_name);
  ~SchemaValidator();
  SchemaValidator(SchemaValidator&&) noexcept;
  SchemaValidator& operator=(SchemaValidator&&) noexcept;

  // Throws InputError for the most specific violation: its JSON pointer,
  // valijson's description, and what the schema expects there.
  void validate(const nlohmann::json& doc, const std::string& file_for_errors) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The validator of an embedded schema, built on first use and then shared
// by every caller and thread of the process: it never changes once built
// (validate() is const), and building one parses every embedded schema,
// which costs more than validating a scene.
const SchemaValidator& shared_schema_validator(std::string_view schema_name);

// The steps every document goes through: validate `doc` against its schema,
// then build(); errors of build() are placed in `file` unless they already
// name another file (a train of the library, a map of an imported model).
template <class Build>
auto parse_validated(const nlohmann::json& doc, std::string_view schema_name, const std::string& file,
                     Build&& build) -> decltype(build()) {
  shared_schema_validator(schema_name).validate(doc, file);
  try {
    return build();
  } catch (const InputError& e) {
    throw e.with_file(file);
  }
}

}  // namespace railvsi

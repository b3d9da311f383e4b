#include "io/schema_validator.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "core/input_error.hpp"
#include "io/embedded_schemas.hpp"
#include "io/json_document.hpp"

namespace railvsi {
namespace {

using nlohmann::json;
using SchemaDocuments = std::map<std::string, json, std::less<>>;

// Every embedded schema, parsed once per process and never changed (each
// validator reads the documents its schema refers to).
const SchemaDocuments& embedded_schema_documents() {
  static const SchemaDocuments docs = [] {
    SchemaDocuments d;
    for (const EmbeddedSchema& s : embedded_schemas()) d.emplace(s.name, json::parse(s.text));
    return d;
  }();
  return docs;
}

// "train.schema.json", "./train.schema.json" and ".../schemas/train.schema.json"
// all name the same embedded schema.
std::string schema_file_name(std::string_view uri) {
  return std::filesystem::path(std::string(uri)).filename().string();
}

// ---- Where in the schemas a place of the document is described. valijson's
// messages do not say what was expected, the schema's descriptions do.

struct SchemaNode {
  const json* node;
  const json* document;  // the schema file the node belongs to, for "#/..." refs
};

class SchemaWalker {
 public:
  explicit SchemaWalker(const SchemaDocuments& docs) : docs_(docs) {}

  // Every schema object that may apply at `node` (through $ref, if/then/else
  // and the combinators).
  void expand(SchemaNode at, std::vector<SchemaNode>& out, int depth = 0) const {
    if (depth > 32 || at.node == nullptr || !at.node->is_object()) return;
    out.push_back(at);
    const json& s = *at.node;
    if (const auto ref = s.find("$ref"); ref != s.end() && ref->is_string())
      expand(resolve(*ref, at.document), out, depth + 1);
    for (const char* branch : {"then", "else"})
      if (const auto it = s.find(branch); it != s.end()) expand({&*it, at.document}, out, depth + 1);
    for (const char* combinator : {"allOf", "anyOf", "oneOf"})
      if (const auto it = s.find(combinator); it != s.end() && it->is_array())
        for (const json& sub : *it) expand({&sub, at.document}, out, depth + 1);
  }

  // The schemas of a member (or of the array elements when index is true).
  std::vector<SchemaNode> step(const std::vector<SchemaNode>& from, const std::string& key,
                               bool index) const {
    std::vector<SchemaNode> out;
    for (const SchemaNode& c : from) {
      const json& s = *c.node;
      if (index) {
        if (const auto items = s.find("items"); items != s.end()) expand({&*items, c.document}, out);
      } else if (const auto props = s.find("properties"); props != s.end() && props->contains(key)) {
        expand({&(*props)[key], c.document}, out);
      }
    }
    return out;
  }

 private:
  SchemaNode resolve(const std::string& ref, const json* document) const {
    const auto hash = ref.find('#');
    const std::string file = ref.substr(0, hash);
    if (!file.empty()) {
      const auto it = docs_.find(schema_file_name(file));
      if (it == docs_.end()) return {nullptr, nullptr};
      document = &it->second;
    }
    const std::string pointer = hash == std::string::npos ? "" : ref.substr(hash + 1);
    const json::json_pointer ptr(pointer);
    return document->contains(ptr) ? SchemaNode{&document->at(ptr), document} : SchemaNode{nullptr, nullptr};
  }

  const SchemaDocuments& docs_;
};

std::string first_description(const std::vector<SchemaNode>& nodes) {
  for (const SchemaNode& n : nodes)
    if (const auto d = n.node->find("description"); d != n.node->end() && d->is_string()) return *d;
  return {};
}

std::vector<std::string> allowed_properties(const std::vector<SchemaNode>& nodes) {
  std::vector<std::string> keys;
  for (const SchemaNode& n : nodes)
    if (const auto props = n.node->find("properties"); props != n.node->end())
      for (const auto& [key, value] : props->items())
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  return keys;
}

// ---- From valijson's error list to one InputError.

bool is_wrapper(const std::string& description) {
  return description.starts_with("Failed to validate") || description.starts_with("Cannot validate item");
}

// valijson reports the innermost violation first and wraps it at every
// enclosing level: the deepest context is the most specific place.
const valijson::ValidationResults::Error& most_specific(
    const std::vector<valijson::ValidationResults::Error>& errors) {
  const valijson::ValidationResults::Error* best = &errors.front();
  for (const auto& e : errors) {
    const bool deeper = e.context.size() > best->context.size();
    const bool as_deep_but_clearer = e.context.size() == best->context.size() &&
                                     is_wrapper(best->description) && !is_wrapper(e.description);
    if (deeper || as_deep_but_clearer) best = &e;
  }
  return *best;
}

// valijson's context ("<root>", "[train]", "[vehicles]", "[0]") walked through
// the document and the schemas at the same time.
struct Place {
  std::string pointer = "/";
  const json* value = nullptr;
  std::vector<SchemaNode> schemas;
};

Place locate(const std::vector<std::string>& context, const json& doc, const SchemaWalker& walker,
             SchemaNode root) {
  Place place;
  place.value = &doc;
  walker.expand(root, place.schemas);
  for (std::size_t i = 1; i < context.size(); ++i) {
    std::string token = context[i];
    if (token.size() >= 2 && token.front() == '[' && token.back() == ']') token = token.substr(1, token.size() - 2);
    const bool index = place.value != nullptr && place.value->is_array();
    place.schemas = walker.step(place.schemas, token, index);
    place.pointer = child_path(place.pointer, token);
    if (place.value == nullptr) continue;
    if (index) {
      const std::size_t k = std::stoul(token);
      place.value = k < place.value->size() ? &(*place.value)[k] : nullptr;
    } else {
      place.value = place.value->is_object() && place.value->contains(token) ? &(*place.value)[token] : nullptr;
    }
  }
  return place;
}

// The name in valijson's "...: 'name'." messages.
std::string quoted_name(const std::string& description) {
  const auto last = description.rfind('\'');
  const auto first = last == std::string::npos ? last : description.rfind('\'', last - 1);
  return first == std::string::npos ? std::string() : description.substr(first + 1, last - first - 1);
}

// valijson's own message, then what the schema says about the value.
std::string with_expectation(const std::string& message, std::string description) {
  if (description.empty()) return message;
  if (!message.starts_with("Expected")) return message + " Expected: " + description;
  if (description.ends_with('.')) description.pop_back();
  return message + " (" + description + ")";
}

bool is_missing_property(const std::string& description) {
  return description.starts_with("Missing required property");
}

// Every property missing at the place of `error`, in one message.
InputError missing_properties_error(const std::vector<valijson::ValidationResults::Error>& errors,
                                    const valijson::ValidationResults::Error& error, const Place& place,
                                    const SchemaWalker& walker, const std::string& file) {
  std::vector<std::string> keys;
  for (const auto& e : errors)
    if (e.context == error.context && is_missing_property(e.description)) {
      const std::string key = quoted_name(e.description);
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  if (keys.size() > 1)
    return InputError(place.pointer, fmt::format("missing required properties '{}'.", fmt::join(keys, "', '")), file);
  return InputError(place.pointer,
                    with_expectation(fmt::format("missing required property '{}'.", keys.front()),
                                     first_description(walker.step(place.schemas, keys.front(), false))),
                    file);
}

InputError to_input_error(const std::vector<valijson::ValidationResults::Error>& errors,
                          const valijson::ValidationResults::Error& error, const Place& place,
                          const SchemaWalker& walker, const std::string& file) {
  const std::string& what = error.description;
  if (what.starts_with("Object contains a property that could not be validated")) {
    const std::string key = quoted_name(what);
    return InputError(child_path(place.pointer, key),
                      fmt::format("unknown property '{}'; allowed here: {}", key,
                                  fmt::join(allowed_properties(place.schemas), ", ")),
                      file);
  }
  if (is_missing_property(what)) return missing_properties_error(errors, error, place, walker, file);
  if (what.starts_with("Value type not permitted") && place.value != nullptr)
    return InputError(place.pointer,
                      with_expectation(fmt::format("wrong type ({}).", place.value->type_name()),
                                       first_description(place.schemas)),
                      file);
  return InputError(place.pointer, with_expectation(what, first_description(place.schemas)), file);
}

}  // namespace

json embedded_schema_json(std::string_view schema_name) {
  for (const EmbeddedSchema& s : embedded_schemas())
    if (s.name == schema_name) return json::parse(s.text);
  throw std::logic_error(fmt::format("schema {} is not compiled into this binary", schema_name));
}

struct SchemaValidator::Impl {
  const SchemaDocuments& documents = embedded_schema_documents();
  std::string root_name;
  valijson::Schema schema;
};

SchemaValidator::SchemaValidator(std::string_view schema_name) : impl_(std::make_unique<Impl>()) {
  impl_->root_name = std::string(schema_name);
  const auto root = impl_->documents.find(schema_name);
  if (root == impl_->documents.end())
    throw std::logic_error(fmt::format("schema {} is not compiled into this binary", schema_name));
  const SchemaDocuments& docs = impl_->documents;
  // valijson owns what fetch returns and hands it back to free.
  auto fetch = [&docs](const std::string& uri) -> const json* {
    const auto it = docs.find(schema_file_name(uri));
    return it == docs.end() ? nullptr : new json(it->second);
  };
  auto free_document = [](const json* document) { delete document; };
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  parser.populateSchema(valijson::adapters::NlohmannJsonAdapter(root->second), impl_->schema, fetch,
                        free_document);
}

const SchemaValidator& shared_schema_validator(std::string_view schema_name) {
  struct Slot {
    std::once_flag built;
    std::optional<SchemaValidator> validator;
  };
  const std::span<const EmbeddedSchema> schemas = embedded_schemas();
  // One slot per embedded schema, each filled once (call_once: threads that
  // ask at the same time wait for the one that builds it).
  static const std::unique_ptr<Slot[]> slots = std::make_unique<Slot[]>(schemas.size());
  for (std::size_t i = 0; i < schemas.size(); ++i) {
    if (schemas[i].name != schema_name) continue;
    Slot& slot = slots[i];
    std::call_once(slot.built, [&] { slot.validator.emplace(schema_name); });
    return *slot.validator;
  }
  throw std::logic_error(fmt::format("schema {} is not compiled into this binary", schema_name));
}

SchemaValidator::~SchemaValidator() = default;
SchemaValidator::SchemaValidator(SchemaValidator&&) noexcept = default;
SchemaValidator& SchemaValidator::operator=(SchemaValidator&&) noexcept = default;

void SchemaValidator::validate(const json& doc, const std::string& file_for_errors) const {
  valijson::Validator validator;  // strict types: "300" is not a number
  valijson::ValidationResults results;
  if (validator.validate(impl_->schema, valijson::adapters::NlohmannJsonAdapter(doc), &results)) return;
  std::vector<valijson::ValidationResults::Error> errors;
  for (valijson::ValidationResults::Error e; results.popError(e);) errors.push_back(e);
  if (errors.empty()) throw InputError("/", "document does not match its schema", file_for_errors);
  const auto& error = most_specific(errors);
  const SchemaWalker walker(impl_->documents);
  const json& root = impl_->documents.at(impl_->root_name);
  const Place place = locate(error.context, doc, walker, {&root, &root});
  throw to_input_error(errors, error, place, walker, file_for_errors);
}

}  // namespace railvsi

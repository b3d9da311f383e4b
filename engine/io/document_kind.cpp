#include "io/document_kind.hpp"

#include <array>
#include <utility>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/irregularity_loader.hpp"
#include "io/json_document.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"

namespace railvsi {
namespace {

using nlohmann::json;

struct KindInfo {
  DocumentKind kind;
  std::string_view name;
  std::string_view schema;
  std::array<std::string_view, 5> keys;  // any of them tells the kind ("" for none)
};

constexpr std::array<KindInfo, 3> kKinds{{
    {DocumentKind::kScene, "scene", "scene.schema.json", {"structure", "speed_kmh", "analysis"}},
    {DocumentKind::kTrain, "train", "train.schema.json", {"vehicles", "moving_forces", "hslm_a", "hslm_b"}},
    {DocumentKind::kIrregularity, "irregularity", "irregularity.schema.json", {"csv", "x_m", "r_m", "spectrum", "defects"}},
}};

const KindInfo& info(DocumentKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k;
  return kKinds.front();
}

std::string known_schemas() {
  std::string list;
  for (const KindInfo& k : kKinds) list += (list.empty() ? "" : ", ") + std::string(k.schema);
  return list;
}

}  // namespace

std::string_view document_kind_name(DocumentKind kind) { return info(kind).name; }

DocumentKind detect_document_kind(const json& doc, const std::string& file) {
  if (!doc.is_object()) throw InputError("/", fmt::format("expected a JSON object, found {}", doc.type_name()), file);
  if (const auto schema = doc.find("$schema"); schema != doc.end() && schema->is_string()) {
    const auto name = std::filesystem::path(schema->get<std::string>()).filename().string();
    for (const KindInfo& k : kKinds)
      if (name == k.schema) return k.kind;
    throw InputError("/$schema", fmt::format("unknown schema '{}'; vsi validate knows {}", name, known_schemas()), file);
  }
  for (const KindInfo& k : kKinds)
    for (std::string_view key : k.keys)
      if (!key.empty() && doc.contains(key)) return k.kind;
  throw InputError("/",
                   fmt::format("cannot tell what kind of document this is: name its schema in \"$schema\" ({}) or "
                               "use the keys of a scene (structure, train, speed_kmh, analysis), a train "
                               "(vehicles, moving_forces, hslm_a or hslm_b) or an irregularity profile (csv, x_m and r_m, "
                               "spectrum or defects)",
                               known_schemas()),
                   file);
}

DocumentKind validate_document(const std::filesystem::path& file) {
  const json doc = read_json_file(file);
  const DocumentKind kind = detect_document_kind(doc, file.string());
  switch (kind) {
    case DocumentKind::kScene: parse_scene(doc, file.parent_path(), file.string()); break;
    case DocumentKind::kTrain: parse_train_document(doc, file); break;
    case DocumentKind::kIrregularity: parse_irregularity_document(doc, file); break;
  }
  return kind;
}

}  // namespace railvsi

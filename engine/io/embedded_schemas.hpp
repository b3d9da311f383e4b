#pragma once
// The JSON schemas of schemas/, compiled into the library at build time
// (engine/io/embed_schemas.cmake) so that validation never depends on where
// the binary runs from.
#include <span>
#include <string_view>

namespace railvsi {

struct EmbeddedSchema {
  std::string_view name;  // file name, e.g. "scene.schema.json"
  std::string_view text;
};

std::span<const EmbeddedSchema> embedded_schemas();

}  // namespace railvsi

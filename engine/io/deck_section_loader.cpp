#include "io/deck_section_loader.hpp"

#include "io/schema_validator.hpp"

namespace railvsi {

void apply_deck_section_document(const nlohmann::json& doc, const std::string& file, Deck3dOptions& options) {
  options = parse_validated(doc, "deck-section.schema.json", file, [&] {
    Deck3dOptions o = options;
    if (doc.at("kind").get<std::string>() == "solid") {
      o.box.reset();
      o.width_m = doc.at("width_m").get<double>();
      o.depth_m = doc.at("depth_m").get<double>();
      return o;
    }
    BoxGirderSection b;
    b.top_width_m = doc.at("top_width_m").get<double>();
    b.top_thickness_m = doc.at("top_thickness_m").get<double>();
    b.bottom_width_m = doc.at("bottom_width_m").get<double>();
    b.bottom_thickness_m = doc.at("bottom_thickness_m").get<double>();
    b.web_thickness_m = doc.at("web_thickness_m").get<double>();
    b.depth_m = doc.at("depth_m").get<double>();
    b.intermediate_diaphragms = doc.value("intermediate_diaphragms", 0);
    check_box_girder(b);  // the relations between the keys
    o.box = b;
    return o;
  });
}

}  // namespace railvsi

#include "study/canonical_json.hpp"

#include <cmath>

namespace railvsi::scheduler {

nlohmann::json canonical_json(const nlohmann::json& doc) {
  using nlohmann::json;
  switch (doc.type()) {
    case json::value_t::object: {
      json out = json::object();  // std::map: keys come out sorted
      for (const auto& [key, value] : doc.items()) out[key] = canonical_json(value);
      return out;
    }
    case json::value_t::array: {
      json out = json::array();
      for (const json& value : doc) out.push_back(canonical_json(value));
      return out;
    }
    case json::value_t::number_float: {
      const double x = doc.get<double>();
      // Integral values below 2^53 are exact as integers: 100.0, 1e2 and 100 agree.
      if (std::isfinite(x) && x == std::trunc(x) && std::abs(x) < 9007199254740992.0)
        return json(static_cast<std::int64_t>(x));
      return doc;
    }
    case json::value_t::number_unsigned:
      return json(doc.get<std::uint64_t>() <= static_cast<std::uint64_t>(INT64_MAX)
                      ? json(static_cast<std::int64_t>(doc.get<std::uint64_t>()))
                      : doc);
    default:
      return doc;
  }
}

std::string canonical_text(const nlohmann::json& doc) {
  // dump() writes doubles in the shortest round-trip form, strings as UTF-8.
  return canonical_json(doc).dump(-1, ' ', false, nlohmann::json::error_handler_t::strict);
}

}  // namespace railvsi::scheduler

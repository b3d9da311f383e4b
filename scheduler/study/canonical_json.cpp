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

std::string canonical_number_text(double x) { return canonical_text(nlohmann::json(x)); }

std::optional<CanonicalNumberSlot> CanonicalNumberSlot::make(nlohmann::json object, const std::string& key) {
  if (!object.is_object()) return std::nullopt;
  // A string no input holds marks the place; it must come out once.
  const std::string mark = "\x01railvsi number slot\x01";
  object[key] = mark;
  const std::string text = canonical_text(object);
  const std::string written = nlohmann::json(mark).dump(-1, ' ', false, nlohmann::json::error_handler_t::strict);
  const std::size_t at = text.find(written);
  if (at == std::string::npos || text.find(written, at + 1) != std::string::npos) return std::nullopt;
  CanonicalNumberSlot slot;
  slot.before_ = text.substr(0, at);
  slot.after_ = text.substr(at + written.size());
  return slot;
}

std::string CanonicalNumberSlot::text(double x) const {
  const std::string number = canonical_number_text(x);
  std::string out;
  out.reserve(before_.size() + number.size() + after_.size());
  out.append(before_).append(number).append(after_);
  return out;
}

}  // namespace railvsi::scheduler

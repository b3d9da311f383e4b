#include "store/scene_parts.hpp"

#include <stdexcept>

namespace railvsi::scheduler {

SceneSplit split_scene(std::string_view scene) {
  static constexpr std::string_view kKey = "\"speed_kmh\":";
  const std::size_t key = scene.find(kKey);
  if (key == std::string_view::npos) return {scene, {}, {}};
  const std::size_t start = key + kKey.size();
  std::size_t end = scene.find_first_of(",}", start);
  if (end == std::string_view::npos) end = scene.size();
  return {scene.substr(0, start), scene.substr(start, end - start), scene.substr(end)};
}

ScenePartCache::ScenePartCache(Database& db)
    : db_(db),
      insert_(db.prepare("INSERT OR IGNORE INTO scene_parts (head, tail) VALUES (?, ?)")),
      find_(db.prepare("SELECT part FROM scene_parts WHERE head = ? AND tail = ?")) {}

std::int64_t ScenePartCache::part(const SceneSplit& split) {
  auto key = std::pair(std::string(split.head), std::string(split.tail));
  if (const auto it = parts_.find(key); it != parts_.end()) return it->second;
  insert_.bind(1, key.first).bind(2, key.second).run();
  find_.reset();
  if (!find_.bind(1, key.first).bind(2, key.second).step()) throw std::logic_error("scene part not stored");
  const std::int64_t part = find_.int64(0);
  find_.reset();
  return parts_.emplace(std::move(key), part).first->second;
}

}  // namespace railvsi::scheduler

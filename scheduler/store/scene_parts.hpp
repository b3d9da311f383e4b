#pragma once
// A job's scene is stored as its part (scene_parts: the text before and after
// its speed, shared by the jobs of one structure, train, profile and step)
// and its speed's text (jobs.scene_speed); the view job_scenes joins them
// back to the very text. The split is the one the store's migration 15 and
// the view's insert trigger make in SQL: after the first "speed_kmh":, up to
// the first ',' or '}' after it (the whole text is the head when it has
// none), so any text comes back to the byte.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "store/sqlite.hpp"

namespace railvsi::scheduler {

struct SceneSplit {
  std::string_view head, speed, tail;
};

SceneSplit split_scene(std::string_view scene);

// The parts of one transaction's scenes: looked up or added once each (a
// part added by a transaction that rolls back is gone, so the map dies with it).
class ScenePartCache {
 public:
  explicit ScenePartCache(Database& db);
  // The number of the scene's part (scene_parts.part), added when new.
  std::int64_t part(const SceneSplit& split);

 private:
  Database& db_;
  Statement insert_, find_;
  std::map<std::pair<std::string, std::string>, std::int64_t, std::less<>> parts_;
};

}  // namespace railvsi::scheduler

#include "store/step_reasons.hpp"

#include <stdexcept>

namespace railvsi::scheduler {

StepReasonCache::StepReasonCache(Database& db)
    : insert_(db.prepare("INSERT OR IGNORE INTO step_reasons (text) VALUES (?)")),
      find_(db.prepare("SELECT number FROM step_reasons WHERE text = ?")) {}

std::int64_t StepReasonCache::number(std::string_view reason) {
  if (const auto it = numbers_.find(reason); it != numbers_.end()) return it->second;
  const std::string text(reason);
  insert_.bind(1, text).run();
  find_.reset();
  if (!find_.bind(1, text).step()) throw std::logic_error("step reason not stored");
  const std::int64_t number = find_.int64(0);
  find_.reset();
  return numbers_.emplace(text, number).first->second;
}

}  // namespace railvsi::scheduler

#include "io/json_document.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <set>
#include <vector>

#include "io/input_file.hpp"

namespace railvsi {

namespace {

// nlohmann keeps the last of duplicate keys; JSON leaves them undefined and
// a user who wrote a key twice meant one of them. The parser callback sees
// every key: one frame per open object or array tracks where it is.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (frames_.size() >= kMaxDepth)
          throw InputError(path(), fmt::format("nesting deeper than {} levels is not a plausible input", kMaxDepth),
                           file_);
        frames_.push_back({event == E::array_start, 0, {}, {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError(path(), fmt::format("duplicate key '{}': JSON objects must not repeat a key", f.key),
                           file_);
        break;
      }
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        element_done();
        break;
      case E::value: element_done(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::set<std::string> keys;
    std::string key;
  };
  // No input needs longer arrays (long profiles come as CSV files); the
  // schema checks after parsing would take minutes on millions of items.
  static constexpr std::size_t kMaxArrayElements = 50000;
  // No input nests deeper than a few levels; 60 million '[' (within the
  // file size limit) took 5.7 GB before the parser gave up.
  static constexpr std::size_t kMaxDepth = 256;
  void element_done() {
    if (frames_.empty() || !frames_.back().array) return;
    if (++frames_.back().index > kMaxArrayElements)
      throw InputError(path(frames_.size() - 1),
                       fmt::format("an array of more than {} elements is not a plausible input", kMaxArrayElements),
                       file_);
  }
  // JSON pointer of the value being parsed in the first `depth` frames.
  std::string path(std::size_t depth) const {
    std::string p = "/";
    for (std::size_t i = 0; i < depth; ++i)
      p = frames_[i].array ? child_path(p, frames_[i].index) : child_path(p, frames_[i].key);
    return p;
  }
  std::string path() const { return path(frames_.size()); }
  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

nlohmann::json parse_json_text(std::string_view text, const std::string& file_for_errors) {
  try {
    return nlohmann::json::parse(text, DuplicateKeyCheck(file_for_errors));
  } catch (const nlohmann::json::exception& e) {
    // A syntax error's message already has "line L, column C"; a number too
    // large for a double says which number. Drop nlohmann's error id.
    std::string message = e.what();
    if (const auto bracket = message.find("] "); message.starts_with("[json.exception") &&
                                                 bracket != std::string::npos)
      message.erase(0, bracket + 2);
    throw InputError("/", "malformed JSON: " + message, file_for_errors);
  }
}

nlohmann::json read_json_file(const std::filesystem::path& file) {
  check_input_file(file, kMaxJsonFileBytes);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("/", "cannot open the file for reading", file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_json_text(text.str(), file.string());
}

std::string child_path(const std::string& parent, std::string_view key) {
  std::string escaped;
  for (char c : key) {
    if (c == '~') escaped += "~0";
    else if (c == '/') escaped += "~1";
    else escaped += c;
  }
  return (parent == "/" ? std::string() : parent) + "/" + escaped;
}

std::string child_path(const std::string& parent, std::size_t index) {
  return child_path(parent, std::to_string(index));
}

std::filesystem::path resolve_relative(const std::filesystem::path& base_dir, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() ? p : base_dir / p;
}

}  // namespace railvsi

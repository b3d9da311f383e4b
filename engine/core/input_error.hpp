#pragma once
// The one exception type of the engine: thrown while a document or a model is
// being accepted, never from inside the time loop. It carries the file and the
// JSON pointer of the offending value so that the user can find it.
#include <stdexcept>
#include <string>
#include <utility>

namespace railvsi {

class InputError : public std::runtime_error {
 public:
  InputError(std::string json_path, const std::string& what, std::string file = {})
      : std::runtime_error(what), json_path_(std::move(json_path)), file_(std::move(file)) {}

  const std::string& json_path() const { return json_path_; }
  const std::string& file() const { return file_; }
  InputError with_file(std::string file) const {
    return InputError(json_path_, what(), file_.empty() ? std::move(file) : file_);
  }
  // "file: /path: message", the form printed by the command line.
  std::string describe() const {
    std::string out;
    if (!file_.empty()) out += file_ + ": ";
    out += (json_path_.empty() ? std::string("/") : json_path_) + ": " + what();
    return out;
  }

 private:
  std::string json_path_;
  std::string file_;
};

}  // namespace railvsi

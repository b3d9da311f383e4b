#pragma once
// Writing several files that belong together (an exported structure and the
// scenes that use it) so that they appear whole or not at all: each is
// written under a temporary name in the target directory, and all are
// renamed once every one is complete. On failure the temporaries are removed
// and the directory holds what it held before.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace railvsi {

struct FileToWrite {
  std::string name;  // file name inside the directory
  std::function<void(const std::filesystem::path&)> write;  // writes the content to the given path
};

// Creates `dir` if needed. Throws std::runtime_error or
// std::filesystem::filesystem_error.
void write_files_together(const std::filesystem::path& dir, const std::vector<FileToWrite>& files);

// A file holding `text`, for FileToWrite::write.
void write_text_file(const std::filesystem::path& file, const std::string& text);

}  // namespace railvsi

#include "io/file_set_writer.hpp"

#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <unistd.h>

namespace railvsi {

void write_text_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
}

void write_files_together(const std::filesystem::path& dir, const std::vector<FileToWrite>& files) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> temporaries;
  const auto temporary = [&](const FileToWrite& f) { return dir / fmt::format("{}.tmp-{}", f.name, ::getpid()); };
  try {
    for (const FileToWrite& f : files) {
      temporaries.push_back(temporary(f));
      f.write(temporaries.back());
    }
  } catch (...) {
    std::error_code ignored;
    for (const auto& t : temporaries) std::filesystem::remove(t, ignored);
    throw;
  }
  for (const FileToWrite& f : files) std::filesystem::rename(temporary(f), dir / f.name);
}

}  // namespace railvsi

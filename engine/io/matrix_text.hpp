#pragma once
// What the text matrix readers share: numbered lines of the file, entries
// that remember their line, and one assembly that checks them.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/types.hpp"

namespace railvsi {

// Lines of a file with their 1-based numbers; errors name the file and a line.
class TextLines {
 public:
  TextLines(const std::filesystem::path& file, std::string json_path);
  bool next(std::string& line);  // false at the end of the file
  long number() const { return number_; }
  const std::string& file() const { return file_; }
  InputError error(const std::string& what) const { return error_at(number_, what); }
  InputError error_at(long line, const std::string& what) const;

 private:
  std::ifstream in_;
  std::string file_, json_path_;
  long number_ = 0;
};

// A matrix file being written: text goes to buffer(), out to the file in
// pieces of about 1 MiB. Throws std::runtime_error naming the file.
class MatrixTextWriter {
 public:
  explicit MatrixTextWriter(const std::filesystem::path& file);
  fmt::memory_buffer& buffer() { return buffer_; }
  void flush_if_large();  // after each column, say
  void finish();          // the rest, and fflush

 private:
  void write_out();
  std::string file_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out_;
  fmt::memory_buffer buffer_;
};

// `s` without leading and trailing blanks and tabs.
inline std::string trim_blanks(std::string_view s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string_view::npos) return {};
  return std::string(s.substr(a, s.find_last_not_of(" \t") - a + 1));
}

struct MatrixEntry {
  int row = 0, col = 0;  // 0-based
  double value = 0.0;
  long line = 0;  // where the value is written
};

enum class MatrixStorage {
  kLowerTriangle,  // symmetric, the lower triangle stored (Matrix Market symmetric, Harwell-Boeing RSA)
  kFull,           // every entry stored; must be symmetric (Matrix Market general, Harwell-Boeing RUA)
  kEitherTriangle  // lower, upper or both; both must agree (Abaqus matrix input)
};

// The n x n matrix of `entries` (duplicates are summed). Refuses, naming the
// line: a non-finite value, an entry above the diagonal of a lower triangle,
// an entry that differs from its transpose by more than 1e-10 of the largest
// entry (the tolerance of StructureModel).
SparseMatrix assemble_checked(std::vector<MatrixEntry> entries, int n, MatrixStorage storage, const TextLines& lines);

}  // namespace railvsi

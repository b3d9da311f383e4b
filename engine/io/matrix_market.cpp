#include "io/matrix_market.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/text_fields.hpp"

namespace railvsi {
namespace {

constexpr const char* kExpectedHeader = "%%MatrixMarket matrix coordinate real|integer general|symmetric";

// Lines of the file with their 1-based numbers; comment and blank lines skipped.
class MatrixMarketLines {
 public:
  MatrixMarketLines(const std::filesystem::path& file, std::string json_path)
      : in_(file), file_(file.string()), json_path_(std::move(json_path)) {
    if (!in_) throw InputError(json_path_, fmt::format("{}: cannot open the file", file_));
  }

  bool next_header(std::string& line) { return read(line); }
  bool next_data(std::string& line) {
    while (read(line))
      if (line.find_first_not_of(" \t\r") != std::string::npos && line.front() != '%') return true;
    return false;
  }
  InputError error(const std::string& what) const {
    return InputError(json_path_, fmt::format("{}:{}: {}", file_, number_, what));
  }

 private:
  bool read(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    return true;
  }
  std::ifstream in_;
  std::string file_, json_path_;
  int number_ = 0;
};

std::vector<std::string> lowercase_words(const std::string& line) {
  std::istringstream ss(line);
  std::vector<std::string> words;
  for (std::string w; ss >> w;) {
    std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return std::tolower(c); });
    words.push_back(w);
  }
  return words;
}

// Returns true for "symmetric", false for "general".
bool read_header(MatrixMarketLines& lines) {
  std::string line;
  if (!lines.next_header(line)) throw lines.error(fmt::format("empty file; expected {}", kExpectedHeader));
  const auto w = lowercase_words(line);
  const bool ok = w.size() == 5 && w[0] == "%%matrixmarket" && w[1] == "matrix" && w[2] == "coordinate" &&
                  (w[3] == "real" || w[3] == "integer" || w[3] == "double") &&
                  (w[4] == "general" || w[4] == "symmetric");
  if (!ok) throw lines.error(fmt::format("unsupported header '{}'; expected {}", line, kExpectedHeader));
  return w[4] == "symmetric";
}

}  // namespace

SparseMatrix read_matrix_market(const std::filesystem::path& file, const std::string& json_path) {
  // Errors in a matrix file are reported at the path that names it.
  const std::uintmax_t bytes = [&] {
    try {
      return check_input_file(file, kMaxMatrixFileBytes, json_path);
    } catch (const InputError& e) {
      throw InputError(json_path, fmt::format("{}: {}", file.string(), e.what()));
    }
  }();
  MatrixMarketLines lines(file, json_path);
  const bool symmetric = read_header(lines);
  std::string line;
  long rows = 0, cols = 0, nnz = 0;
  if (!lines.next_data(line)) throw lines.error("missing the size line 'rows columns entries'");
  if (!parse_fields(line, rows, cols, nnz) || rows <= 0 || cols <= 0 || nnz < 0)
    throw lines.error(fmt::format("expected the size line 'rows columns entries', found '{}'", line));
  if (rows != cols) throw lines.error(fmt::format("matrix is {} x {}; a structure matrix must be square", rows, cols));
  // Checked before anything is allocated from the size line: an entry line
  // "i j v" has at least 6 bytes, and a structure matrix (positive definite,
  // or a mass matrix with its diagonal) has at least one entry per row.
  if (nnz > static_cast<long>(bytes / 6))
    throw lines.error(fmt::format("the size line promises {} entries, more than a file of {} bytes can hold", nnz,
                                  bytes));
  if (rows > std::numeric_limits<int>::max())
    throw lines.error(fmt::format("the size line gives {} rows, more than {}", rows, std::numeric_limits<int>::max()));

  std::vector<Triplet> triplets;
  triplets.reserve(static_cast<std::size_t>(symmetric ? 2 * nnz : nnz));
  for (long k = 0; k < nnz; ++k) {
    if (!lines.next_data(line))
      throw lines.error(fmt::format("the file ends after {} of the {} entries of the size line", k, nnz));
    long i = 0, j = 0;
    double v = 0.0;
    if (!parse_fields(line, i, j, v)) throw lines.error(fmt::format("expected 'row column value', found '{}'", line));
    if (i < 1 || i > rows || j < 1 || j > cols)
      throw lines.error(fmt::format("index ({}, {}) outside the {} x {} matrix (indices are 1-based)", i, j, rows, cols));
    triplets.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), v);
    if (symmetric && i != j) triplets.emplace_back(static_cast<int>(j - 1), static_cast<int>(i - 1), v);
  }
  if (lines.next_data(line)) throw lines.error(fmt::format("more entries than the {} of the size line", nnz));
  if (rows > std::max(nnz, 1L))  // before the column array of `rows` entries is allocated
    throw lines.error(fmt::format("{} rows but only {} entries: a structure matrix has at least one entry per row",
                                  rows, nnz));
  SparseMatrix A(static_cast<int>(rows), static_cast<int>(cols));
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

void write_matrix_market(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric) {
  const auto written = [symmetric](Eigen::Index row, Eigen::Index col) { return !symmetric || row >= col; };
  long count = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) count += written(it.row(), it.col()) ? 1 : 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(file.c_str(), "wb"), &std::fclose);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
  fmt::memory_buffer buffer;
  const auto flush = [&] {
    if (std::fwrite(buffer.data(), 1, buffer.size(), out.get()) != buffer.size())
      throw std::runtime_error(fmt::format("cannot write {}", file.string()));
    buffer.clear();
  };
  fmt::format_to(std::back_inserter(buffer), "%%MatrixMarket matrix coordinate real {}\n% written by railvsi\n{} {} {}\n",
                 symmetric ? "symmetric" : "general", A.rows(), A.cols(), count);
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (written(it.row(), it.col()))
        fmt::format_to(std::back_inserter(buffer), "{} {} {:.17g}\n", it.row() + 1, it.col() + 1, it.value());
    if (buffer.size() > (1u << 20)) flush();
  }
  flush();
  if (std::fflush(out.get()) != 0) throw std::runtime_error(fmt::format("cannot write {}", file.string()));
}

}  // namespace railvsi

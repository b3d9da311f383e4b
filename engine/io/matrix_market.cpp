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
#include "io/matrix_text.hpp"
#include "io/text_fields.hpp"

namespace railvsi {
namespace {

constexpr const char* kExpectedHeader = "%%MatrixMarket matrix coordinate real|integer general|symmetric";

// The next line that is neither blank nor a % comment.
bool next_data(TextLines& lines, std::string& line) {
  while (lines.next(line))
    if (line.find_first_not_of(" \t") != std::string::npos && line.front() != '%') return true;
  return false;
}

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
bool read_header(TextLines& lines) {
  std::string line;
  if (!lines.next(line)) throw lines.error(fmt::format("empty file; expected {}", kExpectedHeader));
  const auto w = lowercase_words(line);
  const bool ok = w.size() == 5 && w[0] == "%%matrixmarket" && w[1] == "matrix" && w[2] == "coordinate" &&
                  (w[3] == "real" || w[3] == "integer" || w[3] == "double") &&
                  (w[4] == "general" || w[4] == "symmetric");
  if (!ok) throw lines.error(fmt::format("unsupported header '{}'; expected {}", line, kExpectedHeader));
  return w[4] == "symmetric";
}

// One value: a number, or nan/inf spelled as strtod spells them (refused later, with the line).
bool parse_entry(const std::string& line, long& i, long& j, double& v) {
  std::istringstream ss(line);
  std::string value;
  if (!(ss >> i >> j >> value)) return false;
  ss >> std::ws;
  if (!ss.eof()) return false;
  char* end = nullptr;
  v = std::strtod(value.c_str(), &end);
  return end == value.c_str() + value.size();
}

}  // namespace

MatrixFile MatrixMarketReader::read(const std::filesystem::path& file, const std::string& json_path) const {
  // Errors in a matrix file are reported at the path that names it.
  const std::uintmax_t bytes = [&] {
    try {
      return check_input_file(file, kMaxMatrixFileBytes, json_path);
    } catch (const InputError& e) {
      throw InputError(json_path, fmt::format("{}: {}", file.string(), e.what()));
    }
  }();
  TextLines lines(file, json_path);
  const bool symmetric = read_header(lines);
  std::string line;
  long rows = 0, cols = 0, nnz = 0;
  if (!next_data(lines, line)) throw lines.error("missing the size line 'rows columns entries'");
  if (!parse_fields(line, rows, cols, nnz) || rows <= 0 || cols <= 0 || nnz < 0)
    throw lines.error(fmt::format("expected the size line 'rows columns entries', found '{}'", line));
  if (rows != cols) throw lines.error(fmt::format("matrix is {} x {}; a structure matrix must be square", rows, cols));
  // Checked before anything is allocated from the size line: an entry line
  // "i j v" has at least 6 bytes, and a structure matrix (positive definite,
  // or a mass matrix with its diagonal) has about one entry per row, so a
  // file cannot describe more rows than it has bytes.
  if (nnz > static_cast<long>(bytes / 6))
    throw lines.error(fmt::format("the size line promises {} entries, more than a file of {} bytes can hold", nnz,
                                  bytes));
  if (rows > static_cast<long>(std::max<std::uintmax_t>(bytes, 1)))
    throw lines.error(fmt::format("the size line gives {} rows, more than a file of {} bytes can describe", rows,
                                  bytes));
  if (rows > std::numeric_limits<int>::max() || nnz > std::numeric_limits<int>::max())
    throw lines.error(fmt::format("{} rows and {} entries: more than this program indexes", rows, nnz));

  std::vector<MatrixEntry> entries;
  entries.reserve(static_cast<std::size_t>(std::min<long>(nnz, 1L << 26)));
  for (long k = 0; k < nnz; ++k) {
    if (!next_data(lines, line))
      throw lines.error(fmt::format("the file ends after {} of the {} entries of the size line", k, nnz));
    long i = 0, j = 0;
    double v = 0.0;
    if (!parse_entry(line, i, j, v)) throw lines.error(fmt::format("expected 'row column value', found '{}'", line));
    if (i < 1 || i > rows || j < 1 || j > cols)
      throw lines.error(fmt::format("index ({}, {}) outside the {} x {} matrix (indices are 1-based)", i, j, rows, cols));
    entries.push_back({static_cast<int>(i - 1), static_cast<int>(j - 1), v, lines.number()});
  }
  if (next_data(lines, line)) throw lines.error(fmt::format("more entries than the {} of the size line", nnz));
  MatrixFile out;
  out.A = assemble_checked(std::move(entries), static_cast<int>(rows),
                           symmetric ? MatrixStorage::kLowerTriangle : MatrixStorage::kFull, lines);
  out.format = symmetric ? "Matrix Market (symmetric)" : "Matrix Market (general)";
  return out;
}

SparseMatrix read_matrix_market(const std::filesystem::path& file, const std::string& json_path) {
  return MatrixMarketReader().read(file, json_path).A;
}

void write_matrix_market(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric) {
  const auto written = [symmetric](Eigen::Index row, Eigen::Index col) { return !symmetric || row >= col; };
  long count = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) count += written(it.row(), it.col()) ? 1 : 0;
  MatrixTextWriter out(file);
  fmt::format_to(std::back_inserter(out.buffer()),
                 "%%MatrixMarket matrix coordinate real {}\n% written by railvsi\n{} {} {}\n",
                 symmetric ? "symmetric" : "general", A.rows(), A.cols(), count);
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (written(it.row(), it.col()))
        fmt::format_to(std::back_inserter(out.buffer()), "{} {} {:.17g}\n", it.row() + 1, it.col() + 1, it.value());
    out.flush_if_large();
  }
  out.finish();
}

}  // namespace railvsi

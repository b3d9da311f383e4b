#include "io/matrix_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "io/abaqus_matrix.hpp"
#include "io/harwell_boeing.hpp"
#include "io/input_file.hpp"
#include "io/matrix_market.hpp"
#include "io/matrix_text.hpp"

namespace railvsi {

// ---- numbered lines

namespace {

// A regular file of bounded size, checked before it is opened: a FIFO
// would block the open itself, /dev/zero would be read without end.
void check_matrix_file(const std::filesystem::path& file, const std::string& json_path) {
  try {
    check_input_file(file, kMaxMatrixFileBytes, json_path);
  } catch (const InputError& e) {
    throw InputError(json_path, fmt::format("{}: {}", file.string(), e.what()));
  }
}

}  // namespace

TextLines::TextLines(const std::filesystem::path& file, std::string json_path)
    : file_(file.string()), json_path_(std::move(json_path)) {
  check_matrix_file(file, json_path_);
  in_.open(file);
  if (!in_) throw InputError(json_path_, fmt::format("{}: cannot open the file", file_));
}

bool TextLines::next(std::string& line) {
  if (!std::getline(in_, line)) return false;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  ++number_;
  return true;
}

InputError TextLines::error_at(long line, const std::string& what) const {
  return InputError(json_path_, fmt::format("{}:{}: {}", file_, line, what));
}

// ---- writing

MatrixTextWriter::MatrixTextWriter(const std::filesystem::path& file)
    : file_(file.string()), out_(std::fopen(file.c_str(), "wb"), &std::fclose) {
  if (!out_) throw std::runtime_error(fmt::format("cannot write {}", file_));
}

void MatrixTextWriter::write_out() {
  if (std::fwrite(buffer_.data(), 1, buffer_.size(), out_.get()) != buffer_.size())
    throw std::runtime_error(fmt::format("cannot write {}", file_));
  buffer_.clear();
}

void MatrixTextWriter::flush_if_large() {
  if (buffer_.size() > (1u << 20)) write_out();
}

void MatrixTextWriter::finish() {
  write_out();
  if (std::fflush(out_.get()) != 0) throw std::runtime_error(fmt::format("cannot write {}", file_));
}

// ---- assembly with checks

SparseMatrix assemble_checked(std::vector<MatrixEntry> entries, int n, MatrixStorage storage, const TextLines& lines) {
  double scale = 0.0;
  for (const MatrixEntry& e : entries) {
    if (!std::isfinite(e.value))
      throw lines.error_at(e.line, fmt::format("entry ({}, {}) is {}: every entry must be a finite number", e.row + 1,
                                               e.col + 1, e.value));
    if (storage == MatrixStorage::kLowerTriangle && e.row < e.col)
      throw lines.error_at(e.line, fmt::format("entry ({}, {}) is above the diagonal, but a symmetric file stores "
                                               "only the lower triangle (row >= column)",
                                               e.row + 1, e.col + 1));
    scale = std::max(scale, std::abs(e.value));
  }
  const auto position = [](const MatrixEntry& a, const MatrixEntry& b) {
    return std::tie(a.col, a.row) < std::tie(b.col, b.row);
  };
  std::stable_sort(entries.begin(), entries.end(), position);
  std::vector<MatrixEntry> merged;  // one per position, duplicates summed, first line kept
  merged.reserve(entries.size());
  for (const MatrixEntry& e : entries) {
    if (!merged.empty() && merged.back().row == e.row && merged.back().col == e.col)
      merged.back().value += e.value;
    else
      merged.push_back(e);
  }
  std::vector<Triplet> triplets;
  triplets.reserve(2 * merged.size());
  for (const MatrixEntry& e : merged) {
    triplets.emplace_back(e.row, e.col, e.value);
    if (e.row == e.col) continue;
    if (storage == MatrixStorage::kLowerTriangle) {
      triplets.emplace_back(e.col, e.row, e.value);
      continue;
    }
    MatrixEntry key;
    key.row = e.col;
    key.col = e.row;
    const auto it = std::lower_bound(merged.begin(), merged.end(), key, position);
    const bool found = it != merged.end() && it->row == key.row && it->col == key.col;
    if (!found && storage == MatrixStorage::kEitherTriangle) {
      triplets.emplace_back(e.col, e.row, e.value);
      continue;
    }
    const double mirror = found ? it->value : 0.0;
    if (std::abs(mirror - e.value) > 1e-10 * scale)
      throw lines.error_at(
          e.line, fmt::format("the matrix is not symmetric: entry ({}, {}) is {:.17g} but entry ({}, {}) is {}; a "
                              "structure matrix must be symmetric",
                              e.row + 1, e.col + 1, e.value, e.col + 1, e.row + 1,
                              found ? fmt::format("{:.17g} (line {})", mirror, it->line) : std::string("not given")));
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
  return A;
}

// ---- DOF names

namespace {

std::string upper(std::string_view s) {
  std::string u(s);
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return std::toupper(c); });
  return u;
}

// Abaqus: DOFs 1-3 displacements, 4-6 rotations (U1..U3, UR1..UR3);
// ANSYS: UX, UY, UZ, ROTX, ROTY, ROTZ.
constexpr std::array<const char*, 6> kAbaqusNames{"U1", "U2", "U3", "UR1", "UR2", "UR3"};
constexpr std::array<const char*, 6> kAnsysNames{"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"};

std::string first_line(const std::filesystem::path& file, int skip) {
  std::ifstream in(file);
  std::string line;
  for (int i = 0; i <= skip; ++i)
    if (!std::getline(in, line)) return {};
  return line;
}

bool looks_like_harwell_boeing(const std::filesystem::path& file) {
  const std::string third = upper(first_line(file, 2));
  if (third.size() < 3) return false;
  return std::string_view("RCP").find(third[0]) != std::string_view::npos &&
         std::string_view("SUHZR").find(third[1]) != std::string_view::npos &&
         std::string_view("AE").find(third[2]) != std::string_view::npos && (third.size() == 3 || third[3] == ' ');
}

bool looks_like_abaqus(const std::filesystem::path& file) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '*') continue;  // keywords and ** comments
    return std::count(line.begin(), line.end(), ',') >= 4;
  }
  return false;
}

}  // namespace

int dof_component(std::string_view name) {
  const std::string u = upper(name);
  for (int c = 0; c < 6; ++c)
    if (u == kAbaqusNames[c] || u == kAnsysNames[c] || u == std::to_string(c + 1)) return c + 1;
  return 0;
}

std::string dof_component_name(int component, bool abaqus) {
  if (component < 1 || component > 6) return fmt::format("DOF {}", component);
  return abaqus ? kAbaqusNames[component - 1] : kAnsysNames[component - 1];
}

// ---- the factory

std::unique_ptr<MatrixReader> make_matrix_reader(const std::filesystem::path& file, const std::string& json_path) {
  check_matrix_file(file, json_path);  // before the content is sniffed
  if (!std::ifstream(file)) throw InputError(json_path, fmt::format("{}: cannot open the file", file.string()));
  if (upper(first_line(file, 0)).starts_with("%%MATRIXMARKET")) return std::make_unique<MatrixMarketReader>();
  if (looks_like_harwell_boeing(file)) return std::make_unique<HarwellBoeingReader>();
  if (looks_like_abaqus(file)) return std::make_unique<AbaqusMatrixReader>();
  const std::string ext = upper(file.extension().string());
  if (ext == ".MTX") return std::make_unique<MatrixMarketReader>();  // gives the header error
  for (const char* hb : {".RSA", ".RUA", ".RSE", ".RUE", ".HB", ".MATRIX"})
    if (ext == hb) return std::make_unique<HarwellBoeingReader>();
  throw InputError(json_path, fmt::format("{}:1: cannot tell the matrix format: expected Matrix Market (first line "
                                          "%%MatrixMarket), Harwell-Boeing (type RSA, RUA, RSE or RUE on line 3) or "
                                          "Abaqus matrix output (lines 'node, dof, node, dof, value')",
                                          file.string()));
}

MatrixFile read_matrix_file(const std::filesystem::path& file, const std::string& json_path) {
  return make_matrix_reader(file, json_path)->read(file, json_path);
}

}  // namespace railvsi

#include "io/abaqus_matrix.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "io/matrix_text.hpp"

namespace railvsi {
namespace {

struct RawEntry {
  DofLabel row, col;
  double value = 0.0;
  long line = 0;
};

// "node, dof, node, dof, value": false when the line is not of that form.
bool parse_line(const std::string& line, RawEntry& e) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim_blanks(std::string_view(line).substr(start, comma == std::string::npos ? comma : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (fields.size() == 6 && fields.back().empty()) fields.pop_back();  // a trailing comma
  if (fields.size() != 5) return false;
  long ints[4];
  for (int k = 0; k < 4; ++k) {
    const auto& f = fields[static_cast<std::size_t>(k)];
    const auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), ints[k]);
    if (ec != std::errc() || p != f.data() + f.size()) return false;
  }
  std::string value = fields[4];
  for (char& c : value)
    if (c == 'D' || c == 'd') c = 'E';
  char* end = nullptr;
  e.value = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size()) return false;
  e.row = {ints[0], static_cast<int>(ints[1])};
  e.col = {ints[2], static_cast<int>(ints[3])};
  return ints[1] == e.row.component && ints[3] == e.col.component;
}

}  // namespace

MatrixFile AbaqusMatrixReader::read(const std::filesystem::path& file, const std::string& json_path) const {
  TextLines lines(file, json_path);
  std::vector<RawEntry> raw;
  for (std::string line; lines.next(line);) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '*') continue;
    RawEntry e;
    if (!parse_line(line, e))
      throw lines.error(fmt::format("expected 'row node, row DOF, column node, column DOF, value', found '{}'", line));
    for (const DofLabel& d : {e.row, e.col})
      if (d.component < 1 || d.component > 6)
        throw lines.error(fmt::format("DOF {} of node {} is not a displacement or rotation (Abaqus DOFs 1-6)",
                                      d.component, d.node));
    e.line = lines.number();
    raw.push_back(e);
  }
  if (raw.empty()) throw lines.error("no matrix entries in the file");
  std::vector<DofLabel> labels;
  labels.reserve(2 * raw.size());
  for (const RawEntry& e : raw) {
    labels.push_back(e.row);
    labels.push_back(e.col);
  }
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  if (labels.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw lines.error("more equations than this program indexes");
  const auto equation = [&](const DofLabel& d) {
    return static_cast<int>(std::lower_bound(labels.begin(), labels.end(), d) - labels.begin());
  };
  std::vector<MatrixEntry> entries;
  entries.reserve(raw.size());
  for (const RawEntry& e : raw) entries.push_back({equation(e.row), equation(e.col), e.value, e.line});
  MatrixFile out;
  out.A = assemble_checked(std::move(entries), static_cast<int>(labels.size()), MatrixStorage::kEitherTriangle, lines);
  out.labels = std::move(labels);
  out.format = "Abaqus matrix input (node, DOF labels)";
  return out;
}

void write_abaqus_matrix(const std::filesystem::path& file, const SparseMatrix& A, const std::vector<DofLabel>& labels) {
  if (static_cast<Eigen::Index>(labels.size()) != A.rows() || !std::is_sorted(labels.begin(), labels.end()) ||
      std::adjacent_find(labels.begin(), labels.end()) != labels.end())
    throw std::invalid_argument("Abaqus export: one label per equation, strictly ordered by (node, DOF)");
  MatrixTextWriter out(file);
  fmt::format_to(std::back_inserter(out.buffer()),
                 "** written by railvsi: row node, row DOF, column node, column DOF, value\n");
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() >= it.col()) {
        const DofLabel& r = labels[static_cast<std::size_t>(it.row())];
        const DofLabel& c = labels[static_cast<std::size_t>(it.col())];
        fmt::format_to(std::back_inserter(out.buffer()), "{}, {}, {}, {}, {:.17g}\n", r.node, r.component, c.node,
                       c.component, it.value());
      }
    out.flush_if_large();
  }
  out.finish();
}

}  // namespace railvsi

#include "io/harwell_boeing.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <memory>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "io/matrix_text.hpp"

namespace railvsi {
namespace {

// A Fortran edit descriptor of the header, e.g. (40I2), (3E25.16), (1P,4D20.12).
struct FieldFormat {
  int per_line = 1;
  int width = 0;
};

FieldFormat parse_field_format(std::string text, bool integer, const TextLines& lines, long line, const char* what) {
  std::string s;
  for (const char c : text)
    if (c != ' ') s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  static const std::regex pattern(R"(^\((?:-?\d+P,?)?(\d*)([IEDFG])(\d+)(?:\.\d+)?(?:E\d+)?\)$)");
  std::smatch m;
  if (!std::regex_match(s, m, pattern) || (integer != (m[2] == "I")))
    throw lines.error_at(line, fmt::format("cannot read the {} format '{}': expected {}", what, text,
                                           integer ? "(nIw), e.g. (10I8)" : "(nEw.d) or (nDw.d), e.g. (3E25.16)"));
  FieldFormat f;
  f.per_line = m[1].length() ? std::stoi(m[1]) : 1;
  f.width = std::stoi(m[3]);
  if (f.per_line < 1 || f.width < 1) throw lines.error_at(line, fmt::format("empty {} format '{}'", what, text));
  return f;
}

// A Fortran real: D exponents, and "1.0-100" (an E format drops the E for
// three-digit exponents).
bool parse_fortran_real(std::string field, double& v) {
  for (char& c : field)
    if (c == 'D' || c == 'd') c = 'E';
  if (field.find_first_of("Ee") == std::string::npos)
    for (std::size_t k = 1; k < field.size(); ++k)
      if ((field[k] == '+' || field[k] == '-') && std::isdigit(static_cast<unsigned char>(field[k - 1]))) {
        field = field.substr(0, k) + 'E' + field.substr(k);
        break;
      }
  char* end = nullptr;
  v = std::strtod(field.c_str(), &end);
  return !field.empty() && end == field.c_str() + field.size();
}

// `count` fields, `per_line` to a line; the line of each is kept when
// `line_of` is given. Fields separated by blanks are read as such (SciPy's
// hb_write prints its E25.16 values 24 wide); otherwise the fixed widths of
// the format split the line (Fortran may print "-1.0E+00-2.0E+00").
template <class T>
std::vector<T> read_fields(TextLines& lines, long count, FieldFormat f, const char* what,
                           std::vector<long>* line_of = nullptr) {
  std::vector<T> out;
  out.reserve(static_cast<std::size_t>(std::min<long>(count, 1L << 26)));
  if (line_of) line_of->reserve(out.capacity());
  std::string line;
  std::vector<std::string> fields;
  while (static_cast<long>(out.size()) < count) {
    if (!lines.next(line))
      throw lines.error(fmt::format("the file ends after {} of the {} {}", out.size(), count, what));
    const long expected = std::min<long>(f.per_line, count - static_cast<long>(out.size()));
    fields.clear();
    std::istringstream ss(line);
    for (std::string token; ss >> token;) fields.push_back(token);
    if (static_cast<long>(fields.size()) != expected) {
      fields.clear();
      for (long slot = 0; slot < expected; ++slot) {
        const std::size_t pos = static_cast<std::size_t>(slot) * static_cast<std::size_t>(f.width);
        fields.push_back(pos < line.size() ? trim_blanks(line.substr(pos, static_cast<std::size_t>(f.width))) : "");
        if (fields.back().empty())
          throw lines.error(fmt::format("expected {} {} on this line (fields of width {}), found '{}'", expected,
                                        what, f.width, line));
      }
    }
    for (const std::string& field : fields) {
      T value{};
      bool ok = false;
      if constexpr (std::is_same_v<T, double>) {
        ok = parse_fortran_real(field, value);
      } else {
        const auto [p, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
        ok = ec == std::errc() && p == field.data() + field.size();
      }
      if (!ok) throw lines.error(fmt::format("cannot read '{}' as one of the {}", field, what));
      out.push_back(value);
      if (line_of) line_of->push_back(lines.number());
    }
  }
  return out;
}

struct Header {
  std::string type;  // e.g. "RSA"
  long nrow = 0, ncol = 0, nnz = 0, neltvl = 0, rhscrd = 0;
  std::string ptrfmt, indfmt, valfmt;
  long format_line = 4;
};

Header read_header(TextLines& lines) {
  std::string line;
  Header h;
  if (!lines.next(line)) throw lines.error("empty file; expected the Harwell-Boeing title line");
  long totcrd = 0, ptrcrd = 0, indcrd = 0, valcrd = 0;
  if (!lines.next(line)) throw lines.error("the file ends before the card counts (line 2)");
  {
    std::istringstream ss(line);
    if (!(ss >> totcrd >> ptrcrd >> indcrd >> valcrd)) throw lines.error("expected the card counts TOTCRD PTRCRD INDCRD VALCRD [RHSCRD]");
    ss >> h.rhscrd;
  }
  if (!lines.next(line) || line.size() < 3) throw lines.error("the file ends before the matrix type line (line 3)");
  h.type = line.substr(0, 3);
  std::transform(h.type.begin(), h.type.end(), h.type.begin(), [](unsigned char c) { return std::toupper(c); });
  {
    std::istringstream ss(line.substr(3));
    if (!(ss >> h.nrow >> h.ncol >> h.nnz)) throw lines.error("expected 'MXTYPE NROW NCOL NNZERO [NELTVL]'");
    ss >> h.neltvl;
  }
  if (h.type[0] == 'C') throw lines.error(fmt::format("type {}: complex matrices are not read (a structure matrix is real)", h.type));
  if (h.type[0] == 'P')
    throw lines.error(fmt::format("type {}: a pattern-only file has no values; export the values (real)", h.type));
  if (h.type[0] != 'R' && h.type[0] != 'I') throw lines.error(fmt::format("unknown matrix type '{}'", h.type));
  if (h.type[1] != 'S' && h.type[1] != 'U')
    throw lines.error(fmt::format("type {}: only symmetric (S) or unsymmetric (U) square matrices are read; a "
                                  "structure matrix is real symmetric",
                                  h.type));
  if (h.type[2] != 'A' && h.type[2] != 'E') throw lines.error(fmt::format("unknown matrix storage in '{}'", h.type));
  if (h.type[2] == 'A' && h.nrow != h.ncol)
    throw lines.error(fmt::format("matrix is {} x {}; a structure matrix must be square", h.nrow, h.ncol));
  if (h.nrow <= 0 || h.ncol <= 0 || h.nnz < 0 || h.nrow > std::numeric_limits<int>::max() ||
      h.nnz > std::numeric_limits<int>::max())
    throw lines.error(fmt::format("sizes NROW {} NCOL {} NNZERO {} are not readable", h.nrow, h.ncol, h.nnz));
  if (valcrd <= 0) throw lines.error("VALCRD is 0: the file holds no values");
  if (!lines.next(line)) throw lines.error("the file ends before the formats line (line 4)");
  h.format_line = lines.number();
  static const std::regex group(R"(\([^)]*\))");
  std::vector<std::string> formats;
  for (auto it = std::sregex_iterator(line.begin(), line.end(), group); it != std::sregex_iterator(); ++it)
    formats.push_back(it->str());
  if (formats.size() < 3) throw lines.error(fmt::format("expected the formats PTRFMT INDFMT VALFMT, found '{}'", line));
  h.ptrfmt = formats[0];
  h.indfmt = formats[1];
  h.valfmt = formats[2];
  if (h.rhscrd > 0 && !lines.next(line)) throw lines.error("the file ends before the right-hand side line (line 5)");
  return h;
}

}  // namespace

MatrixFile HarwellBoeingReader::read(const std::filesystem::path& file, const std::string& json_path) const {
  TextLines lines(file, json_path);
  const Header h = read_header(lines);
  const FieldFormat ptrf = parse_field_format(h.ptrfmt, true, lines, h.format_line, "pointer");
  const FieldFormat indf = parse_field_format(h.indfmt, true, lines, h.format_line, "index");
  const FieldFormat valf = parse_field_format(h.valfmt, false, lines, h.format_line, "value");
  const bool elemental = h.type[2] == 'E';
  const bool symmetric = h.type[1] == 'S';

  const std::vector<long> ptr = read_fields<long>(lines, h.ncol + 1, ptrf, "column pointers");
  const long ptr_line = lines.number();
  if (ptr.front() != 1) throw lines.error_at(ptr_line, fmt::format("the first pointer is {}, not 1", ptr.front()));
  for (long j = 0; j < h.ncol; ++j)
    if (ptr[j + 1] < ptr[j])
      throw lines.error_at(ptr_line, fmt::format("pointer {} ({}) is smaller than pointer {} ({})", j + 2, ptr[j + 1],
                                                 j + 1, ptr[j]));
  if (ptr.back() != h.nnz + 1)
    throw lines.error_at(ptr_line, fmt::format("the last pointer is {}, but NNZERO is {} (expected NNZERO + 1)",
                                               ptr.back(), h.nnz));
  const std::vector<long> ind = read_fields<long>(lines, h.nnz, indf, "row indices");
  const long ind_line = lines.number();
  for (long k = 0; k < h.nnz; ++k)
    if (ind[k] < 1 || ind[k] > h.nrow)
      throw lines.error_at(ind_line, fmt::format("row index {} outside 1..{}", ind[k], h.nrow));

  std::vector<MatrixEntry> entries;
  MatrixFile out;
  if (!elemental) {
    std::vector<long> value_line;
    const std::vector<double> val = read_fields<double>(lines, h.nnz, valf, "values", &value_line);
    entries.reserve(val.size());
    for (long j = 0; j < h.ncol; ++j)
      for (long p = ptr[j] - 1; p < ptr[j + 1] - 1; ++p)
        entries.push_back({static_cast<int>(ind[p] - 1), static_cast<int>(j), val[p], value_line[p]});
  } else {
    // Element e's variables are ind[ptr[e]-1 .. ptr[e+1]-2]; its matrix
    // follows by columns: the lower triangle (symmetric) or all of it.
    long expected = 0;
    for (long e = 0; e < h.ncol; ++e) {
      const long s = ptr[e + 1] - ptr[e];
      expected += symmetric ? s * (s + 1) / 2 : s * s;
    }
    if (expected != h.neltvl)
      throw lines.error_at(3, fmt::format("NELTVL is {}, but the element variable lists need {} values", h.neltvl,
                                          expected));
    std::vector<long> value_line;
    const std::vector<double> val = read_fields<double>(lines, h.neltvl, valf, "element values", &value_line);
    long k = 0;
    for (long e = 0; e < h.ncol; ++e) {
      const long first = ptr[e] - 1, s = ptr[e + 1] - ptr[e];
      for (long c = 0; c < s; ++c)
        for (long r = symmetric ? c : 0; r < s; ++r, ++k) {
          int row = static_cast<int>(ind[first + r] - 1), col = static_cast<int>(ind[first + c] - 1);
          if (symmetric && row < col) std::swap(row, col);  // the lower triangle of the sum
          entries.push_back({row, col, val[k], value_line[k]});
        }
    }
  }
  const int n = static_cast<int>(h.nrow);
  out.A = assemble_checked(std::move(entries), n, symmetric ? MatrixStorage::kLowerTriangle : MatrixStorage::kFull,
                           lines);
  out.format = fmt::format("Harwell-Boeing {}", h.type);
  if (const auto mapping = mapping_file_of(file); !mapping.empty()) {
    out.labels = read_ansys_mapping(mapping, n, json_path);
    out.format += fmt::format(", labels from {}", mapping.filename().string());
  }
  return out;
}

std::filesystem::path mapping_file_of(const std::filesystem::path& matrix_file) {
  for (const char* ext : {".mapping", ".MAPPING"}) {
    auto candidate = matrix_file;
    candidate.replace_extension(ext);
    if (std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return {};
}

std::vector<DofLabel> read_ansys_mapping(const std::filesystem::path& file, int n, const std::string& json_path) {
  TextLines lines(file, json_path);
  std::vector<DofLabel> labels(static_cast<std::size_t>(n));
  std::vector<long> seen(static_cast<std::size_t>(n), 0);
  for (std::string line; lines.next(line);) {
    std::istringstream ss(line);
    std::string first;
    if (!(ss >> first)) continue;
    if (!std::isdigit(static_cast<unsigned char>(first[0]))) continue;  // the heading
    long eqn = 0, node = 0;
    std::string dof, extra;
    const auto [p, ec] = std::from_chars(first.data(), first.data() + first.size(), eqn);
    if (ec != std::errc() || p != first.data() + first.size() || !(ss >> node >> dof) || (ss >> extra))
      throw lines.error(fmt::format("expected 'equation node DOF' (e.g. '12 4 UY'), found '{}'", line));
    if (eqn < 1 || eqn > n) throw lines.error(fmt::format("equation {} outside the matrix's 1..{}", eqn, n));
    const int component = dof_component(dof);
    if (component == 0)
      throw lines.error(fmt::format("DOF label '{}' is not one of UX, UY, UZ, ROTX, ROTY, ROTZ", dof));
    auto& first_seen = seen[static_cast<std::size_t>(eqn - 1)];
    if (first_seen) throw lines.error(fmt::format("equation {} is mapped twice (also on line {})", eqn, first_seen));
    first_seen = lines.number();
    labels[static_cast<std::size_t>(eqn - 1)] = {node, component};
  }
  for (int i = 0; i < n; ++i)
    if (!seen[static_cast<std::size_t>(i)])
      throw lines.error(fmt::format("equation {} of the {} is not mapped to a node and DOF", i + 1, n));
  return labels;
}

void write_ansys_mapping(const std::filesystem::path& file, const std::vector<DofLabel>& labels) {
  MatrixTextWriter out(file);
  fmt::format_to(std::back_inserter(out.buffer()), "Matrix Eqn   Node   DOF\n");
  for (std::size_t i = 0; i < labels.size(); ++i) {
    fmt::format_to(std::back_inserter(out.buffer()), "{:10d} {:6d}   {}\n", i + 1, labels[i].node,
                   dof_component_name(labels[i].component, false));
    out.flush_if_large();
  }
  out.finish();
}

void write_harwell_boeing(const std::filesystem::path& file, const SparseMatrix& A, bool symmetric,
                          const std::string& title) {
  std::vector<long> ptr{1}, ind;
  std::vector<double> val;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (!symmetric || it.row() >= it.col()) {
        ind.push_back(it.row() + 1);
        val.push_back(it.value());
      }
    ptr.push_back(static_cast<long>(ind.size()) + 1);
  }
  const int pw = static_cast<int>(std::to_string(ptr.back()).size()) + 1;
  const int iw = static_cast<int>(std::to_string(A.rows()).size()) + 1;
  const int pn = std::max(1, 80 / pw), in = std::max(1, 80 / iw), vn = 3;
  const auto cards = [](std::size_t count, int per_line) { return static_cast<long>((count + per_line - 1) / per_line); };
  const long ptrcrd = cards(ptr.size(), pn), indcrd = cards(ind.size(), in), valcrd = cards(val.size(), vn);
  MatrixTextWriter writer(file);
  auto out = std::back_inserter(writer.buffer());
  fmt::format_to(out, "{:<72.72}{:<8}\n", title, "railvsi");
  fmt::format_to(out, "{:14d}{:14d}{:14d}{:14d}{:14d}\n", ptrcrd + indcrd + valcrd, ptrcrd, indcrd, valcrd, 0);
  fmt::format_to(out, "{:<14}{:14d}{:14d}{:14d}{:14d}\n", symmetric ? "RSA" : "RUA", A.rows(), A.cols(), val.size(), 0);
  fmt::format_to(out, "{:<16}{:<16}{:<20}\n", fmt::format("({}I{})", pn, pw), fmt::format("({}I{})", in, iw),
                 fmt::format("({}E25.16)", vn));
  const auto block = [&](const auto& values, int per_line, auto&& field) {
    for (std::size_t k = 0; k < values.size(); ++k) {
      field(values[k]);
      if ((k + 1) % static_cast<std::size_t>(per_line) == 0 || k + 1 == values.size()) {
        fmt::format_to(out, "\n");
        writer.flush_if_large();
      }
    }
  };
  block(ptr, pn, [&](long v) { fmt::format_to(out, "{:{}d}", v, pw); });
  block(ind, in, [&](long v) { fmt::format_to(out, "{:{}d}", v, iw); });
  block(val, vn, [&](double v) { fmt::format_to(out, "{:25.16E}", v); });
  writer.finish();
}

}  // namespace railvsi

#include "cli/histories_csv.hpp"

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

namespace railvsi::cli {
namespace {

struct Column {
  std::string name;
  const std::vector<double>* values;
};

std::string csv_table(const std::vector<double>& t_s, const std::vector<Column>& columns) {
  std::string out = "t_s";
  for (const Column& c : columns) out += "," + c.name;
  out += '\n';
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    out += fmt::format("{}", t_s[k]);
    for (const Column& c : columns) out += k < c.values->size() ? fmt::format(",{}", (*c.values)[k]) : ",";
    out += '\n';
  }
  return out;
}

// Written to a temporary file in the same directory, then renamed: a reader
// never sees half a file, even if vsi is killed while writing.
void write_file_atomically(const std::filesystem::path& file, const std::string& content) {
  std::filesystem::path tmp = file;
  tmp += fmt::format(".tmp-{}", ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << content;
    out.close();
    if (!out) {
      std::filesystem::remove(tmp);
      throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
    }
  }
  std::filesystem::rename(tmp, file);
}

std::vector<Column> named_columns(const std::vector<std::string>& names, const std::vector<std::vector<double>>& series,
                                  const std::string& suffix) {
  std::vector<Column> columns;
  for (std::size_t i = 0; i < names.size() && i < series.size(); ++i) columns.push_back({names[i] + suffix, &series[i]});
  return columns;
}

}  // namespace

void write_histories(const Histories& h, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::vector<Column> deck;
  for (std::size_t p = 0; p < h.point_names.size(); ++p) {
    deck.push_back({h.point_names[p] + "_displacement_m", &h.deck_displacement_m.at(p)});
    deck.push_back({h.point_names[p] + "_acceleration_mps2", &h.deck_acceleration_mps2.at(p)});
  }
  write_file_atomically(dir / "deck.csv", csv_table(h.t_s, deck));
  if (!h.wheel_names.empty())
    write_file_atomically(dir / "contact_forces.csv", csv_table(h.t_s, named_columns(h.wheel_names, h.contact_force_N, "_N")));
  if (!h.body_names.empty())
    write_file_atomically(dir / "carbody.csv",
                          csv_table(h.t_s, named_columns(h.body_names, h.carbody_acceleration_mps2, "_acceleration_mps2")));
}

}  // namespace railvsi::cli

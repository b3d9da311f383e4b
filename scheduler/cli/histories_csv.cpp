#include "cli/histories_csv.hpp"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/file_set_writer.hpp"

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

std::vector<Column> named_columns(const std::vector<std::string>& names, const std::vector<std::vector<double>>& series,
                                  const std::string& suffix) {
  std::vector<Column> columns;
  for (std::size_t i = 0; i < names.size() && i < series.size(); ++i) columns.push_back({names[i] + suffix, &series[i]});
  return columns;
}

}  // namespace

// The three files appear together or not at all, even if vsi is killed
// while writing.
void write_histories(const Histories& h, const std::filesystem::path& dir, const HistoryExtras* extras) {
  std::vector<Column> deck;
  if (extras) {
    deck.push_back({"first_axle_x_m", &extras->first_axle_x_m});
    deck.push_back({"in_window", &extras->in_window});
  }
  for (std::size_t p = 0; p < h.point_names.size(); ++p) {
    deck.push_back({h.point_names[p] + "_displacement_m", &h.deck_displacement_m.at(p)});
    deck.push_back({h.point_names[p] + "_acceleration_mps2", &h.deck_acceleration_mps2.at(p)});
    if (extras && p < extras->filtered_acceleration_mps2.size())
      deck.push_back({h.point_names[p] + "_acceleration_filtered_mps2", &extras->filtered_acceleration_mps2[p]});
  }
  const auto table_file = [&h](std::string name, std::vector<Column> columns) {
    return FileToWrite{std::move(name), [&h, columns = std::move(columns)](const std::filesystem::path& file) {
                         write_text_file(file, csv_table(h.t_s, columns));
                       }};
  };
  std::vector<FileToWrite> files{table_file("deck.csv", std::move(deck))};
  if (!h.wheel_names.empty())
    files.push_back(table_file("contact_forces.csv", named_columns(h.wheel_names, h.contact_force_N, "_N")));
  if (!h.body_names.empty())
    files.push_back(
        table_file("carbody.csv", named_columns(h.body_names, h.carbody_acceleration_mps2, "_acceleration_mps2")));
  write_files_together(dir, files);
}

}  // namespace railvsi::cli

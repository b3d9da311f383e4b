#pragma once
// The rows `vsi price --db F --study ID` measured, kept in the study's
// store (table price_rows) so that the compliance report can draw the
// accuracy-price chart from the store alone. One row per run of a job's
// ladder and priced quantity; pricing a job again replaces its rows.
#include <optional>
#include <string>
#include <vector>

#include "planning/accuracy_price.hpp"
#include "store/sqlite.hpp"

namespace railvsi::scheduler {

// Replaces the price rows of (study, job) by those of `price`, in one
// transaction.
void store_price_rows(Database& db, const std::string& study_id, const std::string& job_id, const PriceReport& price);

struct StoredPriceRow {
  std::string job_id;
  int run = 0;
  std::string model, structure, contact_law;
  std::optional<int> modes;
  double dt_s = 0.0;
  std::string status;
  double cpu_s = 0.0, wall_s = 0.0;
  bool reference = false;
  std::string quantity;
  std::optional<double> value, error;
  bool pareto = false;
};

// Every price row of the study, by job (in the study's job order), run and
// the order of price_quantities().
std::vector<StoredPriceRow> read_price_rows(Database& db, const std::string& study_id);

}  // namespace railvsi::scheduler

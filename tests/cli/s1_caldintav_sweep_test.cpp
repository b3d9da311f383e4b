// The S1 HSLM sweep against CALDINTAV's whole curve: HSLM-A1..A10 at 150 to
// 400 km/h (step 10) over a 25 m simply supported span, 15 t/m, f0 =
// 3.55 Hz, 1 % damping, midspan, through `vsi run` (the planner's exact
// modal rung: modes up to 1.2 x the code frequency 31.95 Hz, i.e. 3).
//
// Reference: CALDINTAV 3.0 (UPM Computational Mechanics Group; Software
// Impacts SIMPAC-2024-175; the code at github.com/khanh-nguyen-gia/caldintav,
// commit 06ff19d), its own modal moving-load solver (SkewModal,
// ParaIntegraExact, SkewMovIntegra of functions.py) run headless and
// unmodified on the same bridge with 3 modes, dt = 1 ms, its own HSLM train
// files and its run length (train + span, plus 1 s of free vibration), the
// unfiltered midspan acceleration and displacement: data/s1_caldintav.csv.
// CALDINTAV does not filter; vsi's unfiltered deck acceleration is the
// comparable value.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;
using Key = std::pair<std::string, int>;  // train, speed km/h

struct Reference {
  double a_mps2 = 0.0, w_m = 0.0;
};

std::map<Key, Reference> caldintav_curve() {
  std::ifstream in(std::filesystem::path(RAILVSI_TEST_DATA) / "s1_caldintav.csv");
  std::map<Key, Reference> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("train,", 0) == 0) continue;
    std::stringstream s(line);
    std::string train, speed, a, w;
    std::getline(s, train, ',');
    std::getline(s, speed, ',');
    std::getline(s, a, ',');
    std::getline(s, w, ',');
    out[{train, std::stoi(speed)}] = {std::stod(a), std::stod(w)};
  }
  return out;
}

class S1Sweep : public VsiCliTest {};

TEST_F(S1Sweep, MatchesCaldintavsWholeCurveAtEverySpeedAbove05) {
  const std::map<Key, Reference> reference = caldintav_curve();
  ASSERT_EQ(reference.size(), 260u);  // 10 trains x 26 speeds
  const double L = 25.0, m = 15000.0, f0 = 3.55;
  const double EI = std::pow(2.0 * L * L * f0 / 3.141592653589793, 2) * m;  // f0 = pi / (2 L^2) sqrt(EI / m)
  json trains = json::array();
  for (int k = 1; k <= 10; ++k) trains.push_back("HSLM-A" + std::to_string(k));
  const json study = {{"name", "S1"},
                      {"structure",
                       {{"generator", "bridge-2d"},
                        {"spans_m", {L}},
                        {"continuous", false},
                        {"deck", {{"EI_Nm2", EI}, {"mass_kg_per_m", m}}},
                        {"damping", {{"ratio", 0.01}}},
                        {"track", nullptr}}},
                      {"trains", trains},
                      {"speeds_kmh", {{"from", 150}, {"to", 400}, {"step", 10}}},
                      {"outputs", {{"points", {{{"name", "mid"}, {"x_m", 12.5}}}}}}};
  const auto db = dir_ / "s1.sqlite";
  const VsiRun run = vsi("run '" + write_json("s1.json", study).string() + "' --db '" + db.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string id = study_id_of(run.out);
  ASSERT_FALSE(id.empty()) << run.out;
  const VsiRun csv = vsi("query --db '" + db.string() + "' --study " + id + " --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;

  std::map<Key, double> a_vsi, w_vsi;
  std::stringstream rows(csv.out);
  std::string line;
  while (std::getline(rows, line)) {
    std::stringstream s(line);
    std::string train, irregularity, speed, quantity, location, value;
    for (std::string* f : {&train, &irregularity, &speed, &quantity, &location, &value}) std::getline(s, *f, ',');
    if (!location.empty() || value.empty() || train == "train") continue;
    if (quantity == "deck_acceleration_unfiltered_mps2") a_vsi[{train, std::stoi(speed)}] = std::stod(value);
    if (quantity == "deck_displacement_m") w_vsi[{train, std::stoi(speed)}] = std::stod(value);
  }
  double worst_a = 0.0, worst_w = 0.0;
  int compared = 0;
  for (const auto& [key, ref] : reference) {
    const auto a = a_vsi.find(key), w = w_vsi.find(key);
    // A speed vsi has no value for fails (NaN), it is not skipped.
    const double a_err = a == a_vsi.end() ? std::nan("") : (a->second - ref.a_mps2) / ref.a_mps2;
    const double w_err = w == w_vsi.end() ? std::nan("") : (w->second - ref.w_m) / ref.w_m;
    worst_w = railvsi::testing::worst_of(worst_w, std::abs(w_err));
    if (ref.a_mps2 < 0.5) continue;  // the done-when criterion: every speed with a value >= 0.5 m/s2
    ++compared;
    worst_a = railvsi::testing::worst_of(worst_a, std::abs(a_err));
    EXPECT_LE(std::abs(a_err), 0.025) << key.first << " " << key.second << " km/h: "
                                      << (a == a_vsi.end() ? std::string("no value") : std::to_string(a->second))
                                      << " against " << ref.a_mps2;
  }
  std::printf("[S1] %d speeds with a >= 0.5 m/s2: worst |a error| %.3f %%, worst |w error| %.3f %%\n", compared,
              100.0 * worst_a, 100.0 * worst_w);
  EXPECT_GT(compared, 100);
  // Measured (2026-11-27, the planner's step 1.95 ms, 16 samples a period
  // of 31.95 Hz): worst acceleration error 1.30 % (1.16 % at 0.966 ms;
  // HSLM-A4 at 360 km/h: 2.2644 against 2.2909 m/s2), at the maximum of
  // the entry transient (first axle at 53.7 m in both); vsi at 0.34 ms
  // gives 2.2677 and CALDINTAV at 0.25 ms 2.2931, so -1.1 % remains, not
  // explained yet. At 8 samples a period (3.91 ms, the deck's step before
  // 2026-11-27 17:40 UTC) it was 3.08 %. Tolerance 2.5 % (the issue's
  // criterion; 1.9x the measured).
  EXPECT_LE(worst_a, 0.025);
  // Displacement: measured 0.07 % worst (HSLM-A3, 280 km/h); tolerance 0.2 % (2.9x).
  EXPECT_LE(worst_w, 0.002);
}

}  // namespace
}  // namespace railvsi::test

// The real trains of the library against the figures of their sources, as
// vsi inspect reads them: axle count, first-to-last axle length and total
// mass. The expected figures are typed from the sources (the tables each
// train file cites), not computed by vsi. And the set of them a study names
// as "set:hsl-real".
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

const std::filesystem::path kTrains = std::filesystem::path(RAILVSI_SOURCE_DIR) / "jobs/trains";
constexpr double kG = 9.81;  // of the static wheel loads (train.schema.json, "as")

class RealTrains : public VsiCliTest {
 protected:
  json inspect_train(const std::string& name) const {
    const VsiRun run = vsi("inspect '" + (kTrains / (name + ".json")).string() + "' --format json");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const json report = json::parse(run.out);
    EXPECT_FALSE(report["train"]["sources"].empty()) << name << " lists its sources";
    return report["train"];
  }
  // Sums and offsets of the source tables are exact to their printed digits.
  // Measured: lengths 0 except AVE-S103's 7 x 24.775 + 19.875 (-2.8e-14 m);
  // loads and masses 0 (exact). Tolerances: 8.5e-14 m, and 1e-15 relative
  // (a few ulps) for the sums.
  void expect_figures(const std::string& name, int axles, double length_m, double mass_kg) const {
    SCOPED_TRACE(name);
    const json t = inspect_train(name);
    EXPECT_EQ(t["axles"].get<int>(), axles);
    ASSERT_EQ(t["axle_list"].size(), static_cast<std::size_t>(axles));
    EXPECT_NEAR(t["length_m"].get<double>(), length_m, 8.5e-14);
    EXPECT_NEAR(t["total_static_load_N"].get<double>() / (mass_kg * kG), 1.0, 1e-15);
    if (t.contains("total_mass_kg")) {
      EXPECT_NEAR(t["total_mass_kg"].get<double>() / mass_kg, 1.0, 1e-15);
    }
  }
};

// IAPF-07 Annex C.2 (as transcribed by xc): 2 power cars of 4 axles at
// 195 kN, 12 coaches of 4 axles at 112 kN; last axle at 350.52 m.
TEST_F(RealTrains, Ice2HasTheAxlesLengthAndLoadOfIapfAnnexC) {
  expect_figures("ICE2", 56, 350.52, (8 * 195.0e3 + 48 * 112.0e3) / kG);
}

// IAPF-07 Annex C.2 (as transcribed by xc): 40 axles of 170 kN, last at 356.05 m.
TEST_F(RealTrains, Talgo350HasTheAxlesLengthAndLoadOfIapfAnnexC) {
  expect_figures("Talgo350", 40, 356.05, 40 * 170.0e3 / kG);
}

// CALDINTAV's ave.def: 52 rows, last offset 393.31 m; per unit 4 x 172.1,
// 4 x 170.7, 4 x 131.6, 4 x 161.9, 4 x 169.2, 4 x 167.9, 2 x 160.5 kN.
TEST_F(RealTrains, AveS100HasTheAxlesLengthAndLoadOfItsCaldintavTable) {
  const double unit_N = 4 * 172.1e3 + 4 * 170.7e3 + 4 * 131.6e3 + 4 * 161.9e3 + 4 * 169.2e3 + 4 * 167.9e3 + 2 * 160.5e3;
  expect_figures("AVE-S100", 52, 393.31, 2 * unit_N / kG);
}

// Goicolea (2014), 8 cars: bodies 6 x 47,800 + 2 x 41,200 kg, 16 bogies of
// 3,500 kg, 32 wheelsets of 1,800 kg; bogie centres 17.375 m, axles 2.5 m,
// cars 24.775 m apart (7 x 24.775 + 17.375 + 2.5 = 193.3 m).
TEST_F(RealTrains, AveS103HasTheRealConsistOfGoicolea2014) {
  expect_figures("AVE-S103", 32, 193.3, 6 * 47800.0 + 2 * 41200.0 + 16 * 3500.0 + 32 * 1800.0);
  // Axles 13-20 (cars 4 and 5) carry (41,200 + 7,000 + 7,200) / 4 kg each,
  // the others (47,800 + 7,000 + 7,200) / 4. Measured 0 N off; 1e-15 relative.
  const json t = inspect_train("AVE-S103");
  for (std::size_t a = 0; a < 32; ++a) {
    const double expected_N = ((a >= 12 && a < 20 ? 41200.0 : 47800.0) + 7000.0 + 7200.0) / 4 * kG;
    EXPECT_NEAR(t["axle_list"][a]["static_load_N"].get<double>() / expected_N, 1.0, 1e-15) << "axle " << a + 1;
  }
}

// The library's ICE3: 8 of Goicolea's (2014) intermediate cars.
TEST_F(RealTrains, Ice3IsEightIntermediateCarsOfGoicolea2014) {
  expect_figures("ICE3", 32, 193.3, 8 * (47800.0 + 7000.0 + 7200.0));
}

// Domenech Monforte (2014) rows: 2 power cars (51,500 + 2 x 2,200 + 4 x
// 1,700 kg), 2 half-rakes of 9 bodies (22,525 kg) on 10 bogies (2,900 kg,
// 2 wheelsets of 1,900 kg); 48 axles over 386.435 m (the file's layout).
TEST_F(RealTrains, EurostarHasTheMassesOfItsThesisRows) {
  expect_figures("Eurostar", 48, 386.435, 2 * (51500.0 + 4400.0 + 6800.0) + 2 * (9 * 22525.0 + 10 * 2900.0 + 20 * 1900.0));
}

// Neves et al. (2014), section 5: 46 axles, 380.15 m between the first and
// last axles, "about 17 t" per axle. The tolerance on the mean axle load is
// the paper's rounding (17 t to the tonne: 500 kg); measured 6 kg.
TEST_F(RealTrains, KhstHasTheAxlesLengthAndAxleLoadOfThePaper) {
  const json t = inspect_train("KHST");
  EXPECT_EQ(t["axles"].get<int>(), 46);
  EXPECT_NEAR(t["length_m"].get<double>(), 380.15, 1e-9);
  EXPECT_NEAR(t["total_static_load_N"].get<double>() / kG / 46, 17000.0, 500.0);
}

// Wu & Yang (2003) car (TTB-2D): 16 x (41,750 + 2 x 3,040 + 4 x 1,780 kg);
// 15 x 25 m + 17.5 + 2.5 = 395 m.
TEST_F(RealTrains, Shinkansen300HasSixteenCarsOfWuAndYang) {
  expect_figures("Shinkansen300", 64, 395.0, 16 * (41750.0 + 6080.0 + 7120.0));
}

// EN 1991-2 Annex D Type 4 (as transcribed by pacril): 30 axles of 170 kN;
// first to last axle 18.65 + 21.85 + 8 x 18.7 + 21.85 + 18.65 = 230.6 m.
TEST_F(RealTrains, EnD4TgvAHasTheAxlesLengthAndLoadOfEnAnnexDType4) {
  expect_figures("EN-D4-TGV-A", 30, 230.6, 30 * 170.0e3 / kG);
}

// EN 1991-2 Annex D Type 3 (as transcribed by pacril): 8 power-car axles of
// 200 kN, 13 coaches of 4 axles of 150 kN; first to last axle
// 2 x 16.46 + 13 x 26.4 + 2 x 2.0 = 376.12 m.
TEST_F(RealTrains, EnD3Ice1HasTheAxlesLengthAndLoadOfEnAnnexDType3) {
  expect_figures("EN-D3-ICE1", 60, 376.12, (8 * 200.0e3 + 52 * 150.0e3) / kG);
}

// Cross-checks against a second source: the dimensions of the real cars, as
// published for the trains in service (typed from the pages docs/trains.md
// names under "Cross-checks"), against the axle offsets of the standard's or
// program's table. The offsets carry the tables' printed digits, so the
// differences are exact but for the rounding of the subtraction: measured
// at most 4.3e-14 m; tolerance 1.2e-13 m.
constexpr double kOffsetTol_m = 1.2e-13;

std::vector<double> axle_offsets_m(const json& train) {
  std::vector<double> x;
  for (const json& a : train["axle_list"]) x.push_back(a["offset_m"].get<double>());
  return x;
}

// ICE 2 (de.wikipedia "ICE 2", bahn-seminar.info "Baureihe 402"): bogie
// wheelbase 3,000 mm under the power cars and 2,500 mm under the coaches;
// coaches 26,400 mm long (first axle to first axle of the next coach).
TEST_F(RealTrains, Ice2HasTheBogiesAndCoachLengthOfTheRealIce2) {
  const std::vector<double> x = axle_offsets_m(inspect_train("ICE2"));
  ASSERT_EQ(x.size(), 56U);
  for (std::size_t i : {0U, 2U, 52U, 54U}) EXPECT_NEAR(x[i + 1] - x[i], 3.000, kOffsetTol_m) << "axle " << i + 1;
  for (std::size_t i = 4; i < 52; i += 2) EXPECT_NEAR(x[i + 1] - x[i], 2.500, kOffsetTol_m) << "axle " << i + 1;
  for (std::size_t i = 4; i + 4 < 52; i += 4) {
    EXPECT_NEAR(x[i + 4] - x[i], 26.400, kOffsetTol_m) << "axle " << i + 1;
  }
}

// Renfe S-102 / Talgo 350 (it.wikipedia "Treno RENFE 102"): power-car bogie
// wheelbase 2,650 mm; (intermediate) coaches 13,140 mm long, one axle each.
TEST_F(RealTrains, Talgo350HasThePowerCarBogiesAndCoachLengthOfTheS102) {
  const std::vector<double> x = axle_offsets_m(inspect_train("Talgo350"));
  ASSERT_EQ(x.size(), 40U);
  for (std::size_t unit : {0U, 20U}) {
    for (std::size_t i : {0U, 2U, 16U, 18U}) {
      EXPECT_NEAR(x[unit + i + 1] - x[unit + i], 2.650, kOffsetTol_m) << "axle " << unit + i + 1;
    }
    for (std::size_t i = 5; i < 14; ++i) {
      EXPECT_NEAR(x[unit + i + 1] - x[unit + i], 13.140, kOffsetTol_m) << "axle " << unit + i + 1;
    }
  }
}

// Renfe S-100 (es.wikipedia "Serie 100 de Renfe"): Bo'Bo'+2'2'2'2'2'2'2'2'2'+Bo'Bo',
// i.e. 26 axles a unit, and 200.150 m a unit: the second unit's first axle
// lies 200.150 m behind the first's. The file names no train; this is the
// check of its reading as the S-100 double unit.
TEST_F(RealTrains, AveS100HasTheAxleArrangementAndUnitLengthOfTheS100) {
  const std::vector<double> x = axle_offsets_m(inspect_train("AVE-S100"));
  ASSERT_EQ(x.size(), 2U * (4 + 9 * 2 + 4));
  EXPECT_NEAR(x[26] - x[0], 200.150, kOffsetTol_m);
}

// TGV Atlantique (fr.wikipedia "TGV Atlantique"): axle arrangement
// Bo'Bo'-11x2'-Bo'Bo', 15 two-axle bogies (4 under the power cars, 11 under
// the 10 articulated trailers). The axles pair into bogies of the standard's
// 3.0 m wheelbase, each bogie farther than that from the next (3.3 m at least).
TEST_F(RealTrains, EnD4TgvAHasTheAxleArrangementOfTheTgvAtlantique) {
  const std::vector<double> x = axle_offsets_m(inspect_train("EN-D4-TGV-A"));
  ASSERT_EQ(x.size(), 2U * (2 + 11 + 2));
  for (std::size_t i = 0; i < x.size(); i += 2) {
    EXPECT_NEAR(x[i + 1] - x[i], 3.0, kOffsetTol_m) << "bogie of axles " << i + 1 << ", " << i + 2;
    if (i + 2 < x.size()) {
      EXPECT_GT(x[i + 2] - x[i + 1], 3.0) << "axles " << i + 2 << ", " << i + 3 << " are two bogies";
    }
  }
}

// ICE 1 (dieter-beinhorn.de, bahnspezl.de "Baureihe 401"): 410.70 m with 14
// coaches and two power cars of 20.560 m, so a coach pitch of
// (410.70 - 2 x 20.56) / 14 m. Measured 1.4e-3 m off 26.40 m; tolerance the
// rounding of the published 410.7 m (0.05 m) over 14 coaches, 3.6e-3 m.
TEST_F(RealTrains, EnD3Ice1HasTheCoachPitchOfTheIce1) {
  const std::vector<double> x = axle_offsets_m(inspect_train("EN-D3-ICE1"));
  ASSERT_EQ(x.size(), 8U + 13 * 4);
  const double pitch_m = (410.70 - 2 * 20.56) / 14;
  for (std::size_t i = 4; i + 4 < 56; i += 4) EXPECT_NEAR(x[i + 4] - x[i], pitch_m, 0.05 / 14) << "axle " << i + 1;
}

TEST_F(RealTrains, TextReportShowsTheLayoutMassAndSources) {
  const VsiRun run = vsi("inspect '" + (kTrains / "ICE2.json").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("56 axles over 350.520 m (first to last), total static load 6936.0 kN (707.0 t)"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("sources: Ministerio de Fomento (2007), IAPF-07"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("    56     350.520          195.00"), std::string::npos) << run.out;
}

json set_study(const json& trains) {
  json study = json::parse(read_text(std::filesystem::path(RAILVSI_TEST_DATA) / "small-scene.json"));
  for (const char* key : {"train", "speed_kmh", "irregularity", "$schema", "description"}) study.erase(key);
  study["name"] = "real trains";
  study["trains"] = trains;
  study["speeds_kmh"] = {200};
  return study;
}

TEST_F(RealTrains, SetHslRealStandsForItsTrainsInOrder) {
  const auto file = write_json("study.json", set_study(json::array({"HSLM-A1", "set:hsl-real"})));
  const VsiRun run = vsi("inspect '" + file.string() + "' --format json --modes 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json report = json::parse(run.out);
  std::vector<std::string> names;
  for (const json& t : report["trains"]) {
    names.push_back(t["name"].get<std::string>());
    EXPECT_EQ(t["model"], "moving_forces") << t["name"];
  }
  // jobs/trains/sets/hsl-real.json, in its order, after the study's own.
  EXPECT_EQ(names, (std::vector<std::string>{"HSLM-A1", "ICE2", "Talgo350", "AVE-S100", "EN-D3-ICE1", "EN-D4-TGV-A",
                                             "AVE-S103", "Eurostar", "KHST", "Shinkansen300"}));
  // The service expands it too: one job per train and speed.
  const VsiRun submitted = vsi("submit '" + file.string() + "' --db '" + (dir_ / "r.sqlite").string() + "'");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  EXPECT_NE(submitted.out.find(": 10 jobs, 10 new"), std::string::npos) << submitted.out;
}

TEST_F(RealTrains, UnknownSetIsAnInputErrorAtItsPlaceInTheStudy) {
  // A set's name is one file name of the sets folder, never a path.
  for (const std::string set : {"no-such-set", "../sets/hsl-real"}) {
    const auto file = write_json("study.json", set_study(json::array({"HSLM-A1", "set:" + set})));
    for (const char* command : {"inspect", "submit"}) {
      SCOPED_TRACE(std::string(command) + " " + set);
      const std::string db = std::string(command) == "submit" ? " --db '" + (dir_ / "r.sqlite").string() + "'" : "";
      const VsiRun run = vsi(std::string(command) + " '" + file.string() + "'" + db);
      expect_input_error(run, file, "/trains/1");
      EXPECT_NE(run.err.find("unknown train set '" + set + "'"), std::string::npos) << run.err;
      EXPECT_NE(run.err.find("hsl-real"), std::string::npos) << "lists the sets: " << run.err;
    }
  }
}

// A train listed directly and again through a set is refused at the set's
// place: the study's items, not the expanded list, name it.
TEST_F(RealTrains, TrainGivenTwiceThroughASetIsRefusedAtTheSet) {
  const auto file = write_json("study.json", set_study(json::array({"Talgo350", "HSLM-A1", "set:hsl-real"})));
  const VsiRun run = vsi("submit '" + file.string() + "' --db '" + (dir_ / "r.sqlite").string() + "'");
  expect_input_error(run, file, "/trains/2");
  EXPECT_NE(run.err.find("the same train as /trains/0"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace railvsi::test

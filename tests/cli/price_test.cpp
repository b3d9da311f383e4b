// vsi price on a scene: every error it reports is recomputed here from
// independent `vsi simulate` runs of the same rungs (the scene document
// changed as docs/accuracy-and-price.md says a rung changes it), not from price's code.
#include <cmath>
#include <fstream>

#include "analysis/modal_moving_forces.hpp"
#include "vsi_test_support.hpp"
#include "io/scene_loader.hpp"
#include "io/train_loader.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

// One ICE3 coach over a 15 m simply supported span with no track model,
// Hertz contact, 300 km/h: the policy's dt is 0.25 ms, the finest run
// 0.0625 ms.
json coach_scene() {
  std::ifstream in(train_library_dir() / "ICE3.json");
  json coach = json::parse(in).at("vehicles").at(0);
  coach.erase("count");
  return {{"structure",
           {{"generator", "bridge-2d"},
            {"spans_m", {15.0}},
            {"deck", {{"EI_Nm2", 1.2e10}, {"mass_kg_per_m", 15000}}},
            {"damping", {{"ratio", 0.02}}},
            {"element_length_m", 0.6},
            {"track", nullptr}}},
          {"train", {{"name", "ICE3 coach"}, {"vehicles", json::array({coach})}}},
          {"speed_kmh", 300},
          {"irregularity", nullptr},
          {"analysis", {{"dt_s", 1e-3}, {"contact", {{"law", "hertz"}}}}},
          {"outputs", {{"points", {{{"name", "mid"}, {"x_m", 7.5}}, {{"name", "quarter"}, {"x_m", 3.75}}}}}}};
}

// A price row's rung as a scene document: dt, contact law (linear Hertz
// unilateral), a train of moving forces ("as": "moving_forces"), the modal
// structure with modes up to modal_cutoff_hz for interaction on the modes.
json rung_document(json doc, const json& row, double modal_cutoff_hz = 0.0) {
  doc["analysis"]["dt_s"] = row.at("dt_s");
  if (row.at("model") == "moving_forces") {
    doc["train"]["as"] = "moving_forces";
  } else {
    json contact = {{"law", row.at("contact_law")}};
    if (row.at("contact_law") == "linear-hertz") contact["unilateral"] = true;
    doc["analysis"]["contact"] = contact;
    if (row.at("structure") == "modal") {
      doc["analysis"]["structure"] = "modal";
      doc["analysis"]["cutoff_hz"] = modal_cutoff_hz;
    }
  }
  return doc;
}

// The priced quantities from a vsi simulate summary.
std::map<std::string, std::optional<double>> simulate_values(const json& s) {
  const auto get = [](const json& v) -> std::optional<double> {
    if (v.is_null()) return std::nullopt;
    return v.get<double>();
  };
  std::map<std::string, std::optional<double>> m;
  m["deck_displacement_m"] = get(s.at("deck").at("max_abs_displacement_m"));
  m["deck_acceleration_mps2"] = get(s.at("deck").at("max_abs_acceleration_filtered_mps2"));
  m["deck_acceleration_unfiltered_mps2"] = get(s.at("deck").at("max_abs_acceleration_mps2"));
  m["min_contact_force_N"] = get(s.at("wheels").at("min_contact_force_N"));
  m["unloading_ratio"] = get(s.at("wheels").at("max_unloading_ratio"));
  m["contact_loss_s"] = get(s.at("wheels").at("contact_loss_s"));
  m["carbody_acceleration_mps2"] = get(s.at("vehicles").at("max_abs_carbody_acceleration_mps2"));
  return m;
}

class Price : public VsiCliTest {};

TEST_F(Price, ErrorsAgreeWithIndependentSimulateRuns) {
  const json doc = coach_scene();
  const auto scene = write_json("scene.json", doc);
  const VsiRun run = vsi("price " + scene.string() + " --format json --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json p = json::parse(run.out);
  const json& rows = p.at("rows");
  // Seven rungs (modal and FE moving forces, modal linear Hertz and Hertz,
  // FE rigid, linear Hertz, Hertz) x five steps.
  ASSERT_EQ(rows.size(), 35u);
  EXPECT_NEAR(p.at("policy").at("dt_s").get<double>(), 2.5e-4, 1e-15);
  const json& ref = p.at("reference");
  EXPECT_EQ(ref.at("contact_law"), "hertz");
  EXPECT_EQ(ref.at("structure"), "fe");
  EXPECT_NEAR(ref.at("dt_s").get<double>(), 6.25e-5, 1e-18);

  // Every FE row again through vsi simulate.
  std::vector<std::map<std::string, std::optional<double>>> simulated(rows.size());
  std::optional<std::size_t> ref_row;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const json& row = rows[i];
    if (row.at("structure") != "fe") continue;
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const auto file = write_json("rung.json", rung_document(doc, row));
    const VsiRun sim = vsi("simulate " + file.string());
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const json sim_out = json::parse(sim.out);
    simulated[i] = simulate_values(sim_out);
    // The row's warning codes are the run's, each once.
    std::vector<std::string> codes;
    for (const json& w : sim_out.at("run").at("warnings"))
      if (std::find(codes.begin(), codes.end(), w.at("code").get<std::string>()) == codes.end())
        codes.push_back(w.at("code").get<std::string>());
    EXPECT_EQ(row.at("warnings").get<std::vector<std::string>>(), codes) << row.dump();
    if (row.at("contact_law") == "hertz" && row.at("dt_s") == ref.at("dt_s")) ref_row = i;
  }
  ASSERT_TRUE(ref_row.has_value());
  int compared = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].at("structure") != "fe") continue;
    for (const auto& [q, v] : simulated[i]) {
      const json& reported = rows[i].at("errors").at(q);
      const auto v_ref = simulated[*ref_row].at(q);
      if (!v || !v_ref || *v_ref == 0.0) {
        // Moving forces have no wheels; a zero reference (no contact loss) has no relative error
        // unless the value is zero too.
        if (v && v_ref && *v == 0.0) {
          EXPECT_EQ(reported.get<double>(), 0.0) << q;
        } else {
          EXPECT_TRUE(reported.is_null()) << q << " in row " << i << ": " << reported;
        }
        continue;
      }
      const double expected = (*v - *v_ref) / *v_ref;
      ASSERT_FALSE(reported.is_null()) << q << " in row " << i;
      // Round-off: the same operations in another process.
      EXPECT_NEAR(reported.get<double>(), expected, 1e-12 * std::max(1.0, std::abs(expected)))
          << q << " in row " << i << " (" << rows[i].at("contact_law") << ", dt " << rows[i].at("dt_s") << ")";
      EXPECT_NEAR(rows[i].at("values").at(q).get<double>(), *v, 1e-12 * std::abs(*v)) << q;
      ++compared;
    }
  }
  // 20 FE rows: 5 x 3 deck quantities for moving forces, 15 x 7 for interaction, less the
  // zero-reference ones (no contact loss at this speed).
  EXPECT_GE(compared, 5 * 3 + 15 * 6);

  // The modal rows: the engine's modal rung on the same moving-force scene
  // with the modes up to 1.2 x the code cut-off reported by simulate.
  const json mf = rung_document(doc, rows[0]);
  const auto mf_file = write_json("mf.json", mf);
  const VsiRun mf_run = vsi("simulate " + mf_file.string());
  ASSERT_EQ(mf_run.exit_code, 0) << mf_run.err;
  const double cutoff_hz = json::parse(mf_run.out).at("deck").at("cutoff_hz").get<double>();
  for (const json& row : rows) {
    if (row.at("structure") != "modal" || row.at("model") != "moving_forces") continue;
    Scene s = load_scene(write_json("modal.json", rung_document(doc, row)));
    ModalMovingForceOptions o;
    o.max_frequency_hz = 1.2 * cutoff_hz;
    const ModalBasis basis(s.structure, o);
    const Result r = run_modal_moving_forces(s, basis);
    ASSERT_TRUE(r.status.ok());
    EXPECT_NEAR(row.at("values").at("deck_displacement_m").get<double>(), r.summary.max_abs_displacement_m,
                1e-12 * r.summary.max_abs_displacement_m);
    EXPECT_NEAR(row.at("values").at("deck_acceleration_unfiltered_mps2").get<double>(),
                r.summary.max_abs_acceleration_mps2, 1e-12 * r.summary.max_abs_acceleration_mps2);
    EXPECT_EQ(row.at("modes").get<int>(), basis.num_modes());
  }
  // The modal interaction rows: vsi simulate on the modal structure with
  // the same modes; values to round-off (the same operations in another
  // process).
  int modal_interaction = 0;
  for (const json& row : rows) {
    if (row.at("structure") != "modal" || row.at("model") != "interaction") continue;
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const auto file = write_json("modal-interaction.json", rung_document(doc, row, 1.2 * cutoff_hz));
    const VsiRun sim = vsi("simulate " + file.string());
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const json out = json::parse(sim.out);
    EXPECT_EQ(out.at("run").at("fidelity").at("modes").get<int>(), row.at("modes").get<int>());
    for (const auto& [q, v] : simulate_values(out)) {
      const json& reported = row.at("values").at(q);
      if (!v) {
        EXPECT_TRUE(reported.is_null()) << q;
        continue;
      }
      EXPECT_NEAR(reported.get<double>(), *v, 1e-12 * std::max(1e-12, std::abs(*v)))
          << q << " (" << row.at("contact_law") << ", dt " << row.at("dt_s") << ")";
    }
    ++modal_interaction;
  }
  EXPECT_EQ(modal_interaction, 10);

  // The cheapest rung within 1 % of every quantity is on its Pareto front.
  for (const auto& [q, pick] : p.at("cheapest").items()) {
    if (pick.at("1%").is_null()) continue;
    const auto& front = p.at("pareto").at(q);
    EXPECT_NE(std::find(front.begin(), front.end(), pick.at("1%").at("row")), front.end()) << q;
  }
}

TEST_F(Price, TableAndCsv) {
  json doc = small_scene();
  const auto scene = write_json("scene.json", doc);
  const VsiRun table = vsi("price " + scene.string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("reference: moving_forces / fe / none"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("cheapest within 1 % / 5 %"), std::string::npos);
  const VsiRun csv = vsi("price " + scene.string() + " --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  // Header and 2 moving-force rungs x 5 steps.
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 11);
  EXPECT_EQ(csv.out.rfind("model,structure,contact_law,modes,dt_s,", 0), 0u);
}

TEST_F(Price, UsageErrors) {
  const auto scene = write_json("scene.json", small_scene());
  EXPECT_EQ(vsi("price").exit_code, 2);
  EXPECT_EQ(vsi("price " + scene.string() + " --study abc --db x.sqlite").exit_code, 2);
  const VsiRun missing = vsi("price --db " + (dir_ / "none.sqlite").string() + " --study abcdef");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no such database"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace railvsi::test

// A price row runs its rung through the rung runner, as a worker runs a
// job: priced at the rung and dt a stored job ran with, the row's key
// quantities are the job's stored envelope values, to the bit. The stored
// values are the worker's (vsi run), read back from the store; the row is
// price_scene's, on the job's stored scene.
#include <cmath>

#include "planning/accuracy_price.hpp"
#include "planning/deck_frequencies.hpp"
#include "price/dt_self_check.hpp"
#include "query/study_results.hpp"
#include "scheduler_test_support.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class PriceReproducesJob : public ServiceTest {
 protected:
  // Every job of the study run by `vsi run`, then priced at its own rung and
  // dt; returns how many quantities were compared.
  int compare_every_job(const json& doc) {
    const auto file = write_json("study.json", doc);
    const std::string db = (dir_ / "r.sqlite").string();
    const VsiResult run = vsi({"run", file.string(), "--db", db, "--threads", "1"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    scheduler::Database d(db);
    scheduler::Statement id = d.prepare("SELECT id FROM studies");
    EXPECT_TRUE(id.step());
    const std::string study_id = id.text(0);
    const std::vector<scheduler::JobResult> jobs = scheduler::study_results(d, {study_id, {}, {}, {}, {}, {}});
    EXPECT_FALSE(jobs.empty());
    int compared = 0;
    for (const scheduler::JobResult& job : jobs) {
      SCOPED_TRACE(job.train + " at " + std::to_string(job.speed_kmh) + " km/h");
      const json fidelity = json::parse(job.fidelity);
      EXPECT_TRUE(fidelity.value("escalation", json()).is_null()) << "an escalated job has no single price rung";
      Scene scene = scheduler::load_job_scene(d, job.id);
      scene.analysis.history_stride = 1;  // as vsi price (the job's scene keeps every step too)
      PriceOptions o;
      const DeckFrequencies f = deck_frequencies(*scene.structure);
      o.f0_hz = f.f0_hz;
      o.f3_hz = f.f3_hz;
      o.base_dt_s = job.ran_dt_s;
      o.dt_factors = {1.0};
      const PriceReport p = price_scene(scene, o);
      EXPECT_EQ(p.cutoff_hz, job.cutoff_hz);
      const std::string law = fidelity.at("model") == "moving_forces" ? "none" : fidelity.at("contact_law").get<std::string>();
      const auto row = std::find_if(p.rows.begin(), p.rows.end(), [&](const PriceRow& r) {
        return r.model + "/" + r.structure == fidelity.at("rung").get<std::string>() && r.contact_law == law;
      });
      EXPECT_NE(row, p.rows.end()) << "no price row of rung " << fidelity.at("rung") << " / " << law;
      if (row == p.rows.end()) continue;
      EXPECT_EQ(row->dt_s, job.ran_dt_s);
      EXPECT_EQ(row->status, "ok") << row->message;
      for (std::string_view qv : price_quantities()) {
        const std::string q(qv);
        const std::optional<double> stored = job.overall(q), priced = row->values.at(q);
        SCOPED_TRACE(q);
        EXPECT_EQ(stored.has_value(), priced.has_value());
        if (!stored || !priced) continue;
        // Bit for bit: the same scene, rung, dt, operator and envelope rule.
        EXPECT_TRUE(std::isfinite(*stored));
        EXPECT_EQ(*priced, *stored);
        ++compared;
      }
    }
    return compared;
  }
};

// Moving forces on the modes (the planner's rung for a load model): the
// worker steps them in batches of lanes (ModalSweep), the price one run at a
// time (run_at_rung).
TEST_F(PriceReproducesJob, ModalMovingForceRowIsTheStoredJob) {
  json doc = tiny_study();
  doc["speeds_kmh"] = json::array({150, 250});
  EXPECT_GE(compare_every_job(doc), 2 * 2 * 3);  // 2 trains x 2 speeds x (displacement, two accelerations)
}

// Interaction on FE (the planner's rung for a multibody train): linear
// Hertz, whose wheels here never unload enough to escalate.
TEST_F(PriceReproducesJob, InteractionRowIsTheStoredJob) {
  json doc = tiny_study();
  doc["trains"] = json::array({one_car_train()});
  doc["speeds_kmh"] = json::array({200});
  EXPECT_GE(compare_every_job(doc), 5);
}

}  // namespace
}  // namespace railvsi::test

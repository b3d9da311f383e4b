// vsi serve end to end: a real server process on a free loopback port, a
// real HTTP client, and the vsi commands as the reference (the API must give
// what they print, byte for byte).
#include <chrono>
#include <future>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "serve_process.hpp"
#include "served_studies.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

class ServeTest : public VsiCliTest {
 protected:
  std::filesystem::path db() const { return dir_ / "store.sqlite"; }
  std::unique_ptr<ServeProcess> serve(const std::vector<std::string>& extra = {},
                                      const std::vector<std::string>& env = {}) const {
    std::vector<std::string> args = {"--db", db().string()};
    args.insert(args.end(), extra.begin(), extra.end());
    auto server = std::make_unique<ServeProcess>(args, dir_, env);
    EXPECT_TRUE(server->running()) << server->log();
    return server;
  }
  static json get_json(httplib::Client& c, const std::string& path) {
    const auto r = c.Get(path.c_str());
    if (!r) return json();
    EXPECT_EQ(r->status, 200) << path << ": " << r->body;
    return json::parse(r->body);
  }
  static json post_study(httplib::Client& c, const json& doc, int expected_status = 202) {
    const auto r = c.Post("/api/studies", doc.dump(), "application/json");
    EXPECT_TRUE(r);
    if (!r) return json();
    EXPECT_EQ(r->status, expected_status) << r->body;
    return json::parse(r->body);
  }
  // Polls the study until no job is queued or running (at most timeout_s).
  static json wait_until_finished(httplib::Client& c, const std::string& id, double timeout_s = 300) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    json s;
    while (std::chrono::steady_clock::now() < deadline) {
      s = get_json(c, "/api/studies/" + id);
      if (s.is_object() && s["jobs"]["queued"] == 0 && s["jobs"]["running"] == 0) return s;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    ADD_FAILURE() << "study " << id << " not finished in " << timeout_s << " s: " << s.dump();
    return s;
  }
  std::string query(const std::string& id, const std::string& options) const {
    const VsiRun q = vsi("query --db '" + db().string() + "' --study " + id + " " + options);
    EXPECT_EQ(q.exit_code, 0) << q.err;
    return q.out;
  }
};

TEST_F(ServeTest, SubmitPollThenEnvelopesReportAndJobEqualTheCommands) {
  const auto server = serve({"--threads", "2"});
  const auto c = server->client();
  const json submitted = post_study(*c, hslm_study("served <HSLM>"));
  const std::string id = submitted["id"];
  EXPECT_EQ(submitted["jobs"], 10);  // 2 trains x 5 speeds
  EXPECT_EQ(submitted["new_jobs"], 10);
  // The same study again adds nothing.
  const json again = post_study(*c, hslm_study("served <HSLM>"));
  EXPECT_EQ(again["id"], id);
  EXPECT_EQ(again["new_jobs"], 0);

  const json status = wait_until_finished(*c, id);
  EXPECT_EQ(status["name"], "served <HSLM>");
  EXPECT_EQ(status["jobs"]["total"], 10);
  EXPECT_EQ(status["jobs"]["done"], 10);
  EXPECT_TRUE(status["eta_s"].is_null());  // nothing left

  // Byte for byte what vsi query prints for the same filters.
  for (const auto& [params, options] : std::vector<std::pair<std::string, std::string>>{
           {"format=csv", "--format csv"},
           {"format=json", "--format json"},
           {"format=table", ""},
           {"format=csv&train=HSLM-A2", "--format csv --train HSLM-A2"},
           {"format=csv&speed_min=205&speed_max=215", "--format csv --speed-min 205 --speed-max 215"}}) {
    const auto r = c->Get(("/api/studies/" + id + "/envelopes?" + params).c_str());
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << params;
    EXPECT_EQ(r->body, query(id, options)) << params;
  }
  // The verdict is vsi query's.
  const json queried = json::parse(query(id, "--format json"));
  EXPECT_EQ(status["verdict"], queried["verdict"]);
  // A prefix of the id works as on the command line.
  EXPECT_EQ(get_json(*c, "/api/studies/" + id.substr(0, 8))["id"], id);
  // A filter naming no train of the study: 400 with vsi query's message.
  const auto bad_train = c->Get(("/api/studies/" + id + "/envelopes?train=nope").c_str());
  ASSERT_TRUE(bad_train);
  EXPECT_EQ(bad_train->status, 400);
  EXPECT_NE(bad_train->body.find("HSLM-A1"), std::string::npos) << bad_train->body;  // it lists the trains

  const auto report = c->Get(("/api/studies/" + id + "/report").c_str());
  ASSERT_TRUE(report);
  EXPECT_EQ(report->status, 200);
  EXPECT_EQ(report->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(report->body.find("served &lt;HSLM&gt;"), std::string::npos);
  EXPECT_NE(report->body.find(queried["verdict"].get<std::string>()), std::string::npos);

  // One job's summary: vsi query's record of it.
  const json first = queried["jobs"][0];
  json job = get_json(*c, "/api/jobs/" + first["id"].get<std::string>().substr(0, 10));
  EXPECT_EQ(job["study"], id);
  job.erase("study");
  EXPECT_EQ(job, first);

  const json list = get_json(*c, "/api/studies");
  ASSERT_EQ(list["studies"].size(), 1u);
  EXPECT_EQ(list["studies"][0]["id"], id);
}

TEST_F(ServeTest, BadStudyGives400WithValidatePathAndMessage) {
  const auto server = serve({"--threads", "0"});
  const auto c = server->client();
  json bad = hslm_study("bad");
  bad["speeds_kmh"] = json::array({200, -5});
  const json body = post_study(*c, bad, 400);
  const VsiRun validate = vsi("validate '" + write_json("bad.json", bad).string() + "'");
  EXPECT_EQ(validate.exit_code, 2);
  // validate: "error: <file>: <path>: <message>"; the API: {"path", "message"}.
  EXPECT_NE(validate.err.find(": " + body["path"].get<std::string>() + ": " + body["message"].get<std::string>()),
            std::string::npos)
      << validate.err << " vs " << body.dump();
  EXPECT_EQ(body["path"], "/speeds_kmh/1");
  // Not JSON at all.
  const auto garbage = c->Post("/api/studies", "{not json", "application/json");
  ASSERT_TRUE(garbage);
  EXPECT_EQ(garbage->status, 400);
  // Nothing was queued.
  EXPECT_EQ(get_json(*c, "/api/studies")["studies"].size(), 0u);
}

TEST_F(ServeTest, UnknownStudyOrJobIs404AndOversizedBodyIs413) {
  const auto server = serve({"--threads", "0", "--max-body-mb", "0.01"});
  const auto c = server->client();
  for (const std::string path : {"/api/studies/0123456789ab", "/api/studies/0123456789ab/envelopes?format=csv",
                                 "/api/studies/0123456789ab/report", "/api/jobs/0123456789ab", "/api/nothing"}) {
    const auto r = c->Get(path.c_str());
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_TRUE(json::parse(r->body).contains("error")) << path << ": " << r->body;
  }
  const auto cancel = c->Post("/api/studies/0123456789ab/cancel", "", "application/json");
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 404);
  // 0.01 MB = 10,485 bytes; the study padded with spaces to 20,000.
  std::string big = hslm_study("big").dump();
  big.append(20000 - big.size(), ' ');
  const auto r = c->Post("/api/studies", big, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(get_json(*c, "/api/studies")["studies"].size(), 0u);
}

TEST_F(ServeTest, TokenIsRequiredOffLoopbackAndCheckedOnEveryApiRequest) {
  // Another address without a token: refused at start (exit 2).
  ServeProcess open_server({"--db", db().string(), "--bind", "0.0.0.0"}, dir_);
  EXPECT_FALSE(open_server.running());
  EXPECT_EQ(open_server.exit_code(), 2) << open_server.log();
  EXPECT_NE(open_server.log().find("token"), std::string::npos);

  // From the environment; every /api request checks it, the page does not need it.
  const auto server = serve({"--threads", "0"}, {"RAILVSI_TOKEN=s3cret-token"});
  const auto c = server->client();
  const auto posted = c->Post("/api/studies", hslm_study("t").dump(), "application/json");
  ASSERT_TRUE(posted);
  EXPECT_EQ(posted->status, 401);
  EXPECT_EQ(token_statuses(*c, "s3cret-token"), (std::vector<int>{401, 401, 200}));
  const auto page = httplib::Client("127.0.0.1", server->port()).Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
}

TEST_F(ServeTest, CancelAndRetryAsTheCommandsThenVsiWorkFinishes) {
  const auto server = serve({"--threads", "0"});  // accept only
  const auto c = server->client();
  const std::string id = post_study(*c, hslm_study("cancelled"))["id"];
  const auto cancel = c->Post(("/api/studies/" + id + "/cancel").c_str(), "", "application/json");
  ASSERT_TRUE(cancel);
  EXPECT_EQ(json::parse(cancel->body)["cancelled"], 10);
  EXPECT_EQ(json::parse(cancel->body)["left_for_other_studies"], 0);
  EXPECT_EQ(get_json(*c, "/api/studies/" + id)["jobs"]["cancelled"], 10);
  const auto retry = c->Post(("/api/studies/" + id + "/retry").c_str(), "", "application/json");
  ASSERT_TRUE(retry);
  EXPECT_EQ(json::parse(retry->body)["queued"], 10);
  EXPECT_EQ(get_json(*c, "/api/studies/" + id)["jobs"]["queued"], 10);
  // The queue is the store's: a vsi work process beside the server runs it.
  const VsiRun work = vsi("work --db '" + db().string() + "' --threads 2");
  EXPECT_EQ(work.exit_code, 0) << work.err;
  EXPECT_EQ(get_json(*c, "/api/studies/" + id)["jobs"]["done"], 10);
}

TEST_F(ServeTest, TwoClientsSubmittingAtOnceBothGetTheirStudy) {
  const auto server = serve({"--threads", "0"});
  auto submit = [&](const std::string& name) {
    const auto c = server->client();
    const auto r = c->Post("/api/studies", hslm_study(name, 4).dump(), "application/json");
    return r ? std::make_pair(r->status, r->body) : std::make_pair(-1, std::string());
  };
  auto a = std::async(std::launch::async, submit, "client A");
  auto b = std::async(std::launch::async, submit, "client B");
  const auto ra = a.get(), rb = b.get();
  ASSERT_EQ(ra.first, 202) << ra.second;
  ASSERT_EQ(rb.first, 202) << rb.second;
  const auto c = server->client();
  const json list = get_json(*c, "/api/studies");
  ASSERT_EQ(list["studies"].size(), 2u);
  std::set<std::string> names;
  for (const json& s : list["studies"]) {
    names.insert(s["name"].get<std::string>());
    EXPECT_EQ(s["jobs"]["queued"], 8);  // 2 trains x 4 speeds each
  }
  EXPECT_EQ(names, (std::set<std::string>{"client A", "client B"}));
}

TEST_F(ServeTest, SigtermGivesRunningJobsBackAndSigkillThenRestartLosesNothing) {
  const json doc = multibody_study("killed", 12);
  auto server = serve({"--threads", "1", "--lease-s", "3"});
  std::string id;
  {
    const auto c = server->client();
    id = post_study(*c, doc)["id"];
    // Mid-study: some done, some not.
    json s;
    for (int i = 0; i < 1200; ++i) {
      s = get_json(*c, "/api/studies/" + id);
      if (s["jobs"]["done"] >= 2) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_GE(s["jobs"]["done"], 2);
    ASSERT_GT(s["jobs"]["queued"], 0) << "the study finished before the kill: make it longer";
  }
  EXPECT_EQ(server->stop(SIGKILL), 128 + SIGKILL);
  const auto killed_at = std::chrono::steady_clock::now();
  // Restarted: the dead server's running jobs come back when their 3 s lease expires.
  server = serve({"--threads", "1", "--lease-s", "3"});
  {
    const auto c = server->client();
    const json s = get_json(*c, "/api/studies/" + id);
    ASSERT_GT(s["jobs"]["queued"].get<int>() + s["jobs"]["running"].get<int>(), 0);
    // SIGTERM while a job runs: it goes back to the queue at once (vsi work's
    // rule). A live lease 4 s after the kill is this server's: the dead
    // one's (3 s) are no longer renewed.
    for (int i = 0; i < 1500; ++i) {
      const json jobs = get_json(*c, "/api/studies/" + id)["jobs"];
      if (std::chrono::steady_clock::now() - killed_at > std::chrono::seconds(4) &&
          jobs["running"].get<int>() - jobs["stale_leases"].get<int>() > 0)
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  EXPECT_EQ(server->stop(SIGTERM), 128 + SIGTERM);
  EXPECT_NE(server->log().find("went back to the queue"), std::string::npos) << server->log();
  const VsiRun status = vsi("status --db '" + db().string() + "'");
  EXPECT_NE(status.out.find("queued, 0 running, "), std::string::npos) << status.out;

  server = serve({"--threads", "2", "--lease-s", "3"});
  const auto c = server->client();
  const json done = wait_until_finished(*c, id);
  EXPECT_EQ(done["jobs"]["done"], 12);
  EXPECT_EQ(done["jobs"]["failed"], 0);
  // Nothing lost, nothing twice: the envelopes equal those of one
  // uninterrupted vsi run of the same study into another store.
  const auto served = c->Get(("/api/studies/" + id + "/envelopes?format=csv").c_str());
  ASSERT_TRUE(served);
  const auto file = write_json("killed.json", doc);
  const VsiRun reference = vsi("run '" + file.string() + "' --db '" + (dir_ / "reference.sqlite").string() + "'");
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  const VsiRun ref_csv = vsi("query --db '" + (dir_ / "reference.sqlite").string() + "' --study " + id +
                             " --format csv");
  EXPECT_EQ(served->body, ref_csv.out);
  EXPECT_EQ(std::count(served->body.begin(), served->body.end(), '\n'), std::count(ref_csv.out.begin(), ref_csv.out.end(), '\n'));
}

}  // namespace
}  // namespace railvsi::test

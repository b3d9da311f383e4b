// The dashboard at `/` in headless Chromium (Debian's chromium, installed by
// tests/setup's test tools) against a real vsi serve: the DOM its script
// builds from the API shows the study, its progress and its links. Also the
// OpenAPI document: every route it lists is one the server answers.
#include <filesystem>
#include <regex>

#include <nlohmann/json.hpp>

#include "../cli/vsi_test_support.hpp"
#include "serve_process.hpp"
#include "served_studies.hpp"

namespace railvsi::test {
namespace {

using nlohmann::json;

std::string chromium() {
  for (const char* name : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
    if (std::filesystem::exists(name)) return name;
  return {};
}

class DashboardTest : public VsiCliTest {
 protected:
  // Submits the small study to a server with two workers; waits until done.
  std::string submit_and_finish(const ServeProcess& server) const {
    const auto c = server.client();
    const auto posted = c->Post("/api/studies", hslm_study("dashboard study", 4).dump(), "application/json");
    EXPECT_TRUE(posted && posted->status == 202);
    const std::string id = posted ? json::parse(posted->body).value("id", "") : "";
    for (int i = 0; i < 600; ++i) {
      const auto r = c->Get(("/api/studies/" + id).c_str());
      if (r && r->status == 200 && json::parse(r->body)["jobs"]["done"] == 8) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return id;
  }
};

TEST_F(DashboardTest, HeadlessChromiumShowsTheStudyWithItsProgressAndLinks) {
  const std::string browser = chromium();
  ASSERT_FALSE(browser.empty()) << "Debian's chromium is not installed (tests/setup installs it)";
  ServeProcess server({"--db", (dir_ / "store.sqlite").string(), "--threads", "2"}, dir_);
  ASSERT_TRUE(server.running()) << server.log();
  const std::string id = submit_and_finish(server);
  ASSERT_FALSE(id.empty());
  // The page's script fetches /api/studies; virtual time lets it finish.
  const auto dom_file = dir_ / "dom.html", log_file = dir_ / "chromium.log";
  const std::string dump = "timeout 120 " + browser +
                           " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run "
                           "--user-data-dir='" +
                           (dir_ / "profile").string() + "' --virtual-time-budget=5000 --dump-dom 'http://127.0.0.1:" +
                           std::to_string(server.port()) + "/' >'" + dom_file.string() + "' 2>'" + log_file.string() +
                           "'";
  ASSERT_EQ(std::system(dump.c_str()), 0) << read_text(log_file);
  const std::string dom = read_text(dom_file);
  EXPECT_NE(dom.find("<tr data-study=\"" + id + "\">"), std::string::npos) << dom;
  EXPECT_NE(dom.find("dashboard study"), std::string::npos);
  // Its progress bar: 8 of 8 jobs finished, and the FAIL verdict vsi query gives.
  EXPECT_NE(dom.find("aria-valuenow=\"8\" aria-valuemax=\"8\""), std::string::npos) << dom;
  EXPECT_NE(dom.find("100 %"), std::string::npos);
  const VsiRun query = vsi("query --db '" + (dir_ / "store.sqlite").string() + "' --study " + id + " --format json");
  const std::string verdict = json::parse(query.out)["verdict"];
  EXPECT_NE(dom.find(">" + verdict + "</span>"), std::string::npos) << dom;
  for (const std::string link : {"/envelopes?format=table", "/envelopes?format=csv", "/report"})
    EXPECT_NE(dom.find("href=\"/api/studies/" + id + link + "\""), std::string::npos) << link;
  // No external asset: nothing the page loads names another host.
  const std::string page = server.client()->Get("/")->body;
  EXPECT_FALSE(std::regex_search(page, std::regex(R"((src|href)=["']?(https?:)?//)"))) << "external asset";
}

TEST_F(DashboardTest, EveryRouteOfTheOpenApiDocumentIsAnswered) {
  const json api = json::parse(read_text(std::filesystem::path(RAILVSI_SOURCE_DIR) / "schemas/http-api.openapi.json"));
  ServeProcess server({"--db", (dir_ / "store.sqlite").string(), "--threads", "2"}, dir_);
  ASSERT_TRUE(server.running()) << server.log();
  const std::string id = submit_and_finish(server);
  const VsiRun query = vsi("query --db '" + (dir_ / "store.sqlite").string() + "' --study " + id + " --format json");
  const std::string job = json::parse(query.out)["jobs"][0]["id"];
  const auto c = server.client();
  int routes = 0;
  for (const auto& [path, item] : api["paths"].items()) {
    const std::string url = std::regex_replace(std::regex_replace(path, std::regex("\\{id\\}"), id),
                                               std::regex("\\{job\\}"), job);
    for (const auto& [method, operation] : item.items()) {
      if (method == "parameters") continue;
      // POST /api/studies with the study (again: 202, nothing new); the others without a body.
      const auto r = method == "get" ? c->Get(url.c_str())
                                     : c->Post(url.c_str(), url == "/api/studies" ? hslm_study("dashboard study", 4).dump() : "",
                                               "application/json");
      ASSERT_TRUE(r) << method << " " << url;
      EXPECT_TRUE(operation["responses"].contains(std::to_string(r->status)))
          << method << " " << url << ": " << r->status << " is not among the document's responses";
      EXPECT_LT(r->status, 300) << method << " " << url << ": " << r->body;
      ++routes;
    }
  }
  EXPECT_EQ(routes, 8);  // the API of issue 38: 2 on /api/studies, 5 on a study, 1 on a job
}

}  // namespace
}  // namespace railvsi::test

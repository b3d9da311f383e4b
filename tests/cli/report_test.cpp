// vsi report end to end: a small study run through the real binary, its
// report written, then opened in headless Chromium (Debian's chromium).
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "png_image.hpp"
#include "vsi_test_support.hpp"

namespace railvsi::test {
namespace {

// Two HSLM trains over the 25 m span of the README example (light deck:
// its resonances exceed the ballasted limit), five speeds: 10 quick jobs.
nlohmann::json small_study() {
  return nlohmann::json::parse(R"({
    "name": "report test <HSLM>",
    "structure": {
      "generator": "bridge-2d", "spans_m": [25], "continuous": false,
      "deck": {"EI_Nm2": 7.694e10, "mass_kg_per_m": 15000},
      "damping": {"ratio": 0.01}, "track": null
    },
    "trains": ["HSLM-A1", "HSLM-A2"],
    "speeds_kmh": {"from": 200, "to": 400, "step": 50},
    "analysis": {"hht_alpha": -0.05},
    "outputs": {"points": [{"name": "quarter", "x_m": 6.25}, {"name": "midspan", "x_m": 12.5}]},
    "checks": {"deck_acceleration_limit_mps2": 3.5}
  })");
}

std::string strip_date_line(std::string html) {
  return std::regex_replace(html, std::regex("<span class=\"small\" id=\"date\">[^<]*</span>"), "");
}

std::string chromium() {
  for (const char* name : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
    if (std::filesystem::exists(name)) return name;
  return {};
}

class ReportTest : public VsiCliTest {
 protected:
  // Submits (and, if `work`, runs) the small study; returns its id.
  std::string submit(const nlohmann::json& study, bool work) {
    const auto file = write_json("study.json", study);
    const VsiRun s = vsi("submit '" + file.string() + "' --db '" + db().string() + "'");
    EXPECT_EQ(s.exit_code, 0) << s.err;
    const std::string id = study_id_of(s.out);
    EXPECT_FALSE(id.empty()) << s.out;
    if (work) {
      const VsiRun w = vsi("work --db '" + db().string() + "' --threads 2");
      EXPECT_EQ(w.exit_code, 0) << w.err;
    }
    return id;
  }
  std::filesystem::path db() const { return dir_ / "study.sqlite"; }
  VsiRun report(const std::string& id, const std::string& out, const std::string& extra = "") const {
    return vsi("report --db '" + db().string() + "' --study " + id + " --out '" + (dir_ / out).string() + "' " + extra);
  }
};

TEST_F(ReportTest, ReportShowsEveryTrainVerdictPlotAndInput) {
  const std::string id = submit(small_study(), true);
  const VsiRun r = report(id, "report.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report.html"), std::string::npos);
  const std::string html = read_text(dir_ / "report.html");
  for (const char* text : {"HSLM-A1", "HSLM-A2", "Peak deck acceleration", "EN 1990 A2.4.4.2.1(4)P", "FAIL",
                           "Deflection under alpha x Phi x LM71", "Dynamic load effect", "LM71", "Governing cases", "Deck acceleration at",
                           "evaluation window", "class=\"mark\"", "f0, first deck bending frequency", id.c_str(), "report test &lt;HSLM&gt;"})
    EXPECT_NE(html.find(text), std::string::npos) << text;
  // Self-contained: no script, nothing loaded from anywhere.
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find(" src="), std::string::npos);
  EXPECT_EQ(html.find(" href="), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  // The study exceeds 3.5 m/s2 at resonance: exit 4 with --fail-on-exceeded.
  EXPECT_EQ(report(id, "again.html", "--fail-on-exceeded").exit_code, 4);
}

TEST_F(ReportTest, CancelledStudyIsIncompleteNeverPass) {
  const std::string id = submit(small_study(), false);
  ASSERT_EQ(vsi("cancel --db '" + db().string() + "' --study " + id).exit_code, 0);
  const VsiRun r = report(id, "report.html", "--fail-on-exceeded");
  EXPECT_EQ(r.exit_code, 5) << r.out << r.err;
  const std::string html = read_text(dir_ / "report.html");
  EXPECT_NE(html.find("Overall: <span class=\"verdict INCOMPLETE\">INCOMPLETE</span>"), std::string::npos);
  // Every check on job results is INCOMPLETE (10 cases, 10 without a
  // value); only the static LM71 deflection, which needs no job, may pass.
  const auto row = [&](const std::string& check) {
    const auto at = html.find("data-check=\"" + check + "\"");
    return at == std::string::npos ? std::string() : html.substr(at, html.find("</tr>", at) - at);
  };
  EXPECT_NE(row("deck_acceleration").find("10 (10)"), std::string::npos) << row("deck_acceleration");
  EXPECT_NE(row("deck_acceleration").find("INCOMPLETE"), std::string::npos);
  EXPECT_NE(row("dynamic_enhancement").find("INCOMPLETE"), std::string::npos) << row("dynamic_enhancement");
  EXPECT_NE(row("lm71_deflection").find("PASS"), std::string::npos);
}

TEST_F(ReportTest, SameStoreGivesTheSameBytes) {
  const std::string id = submit(small_study(), true);
  ASSERT_EQ(report(id, "a.html").exit_code, 0);
  ASSERT_EQ(report(id, "b.html").exit_code, 0);
  EXPECT_EQ(strip_date_line(read_text(dir_ / "a.html")), strip_date_line(read_text(dir_ / "b.html")));
  ::setenv("SOURCE_DATE_EPOCH", "1767225600", 1);
  ASSERT_EQ(report(id, "c.html").exit_code, 0);
  ASSERT_EQ(report(id, "d.html").exit_code, 0);
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_EQ(read_text(dir_ / "c.html"), read_text(dir_ / "d.html"));
  EXPECT_NE(read_text(dir_ / "c.html").find("2026-01-01 00:00 UTC"), std::string::npos);
}

TEST_F(ReportTest, HeadlessChromiumRendersTheReport) {
  const std::string browser = chromium();
  ASSERT_FALSE(browser.empty()) << "Debian's chromium is not installed (tests/setup installs it)";
  const std::string id = submit(small_study(), true);
  ASSERT_EQ(report(id, "report.html").exit_code, 0);
  const std::string url = "file://" + (dir_ / "report.html").string();
  const std::string flags = " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run "
                            "--user-data-dir='" + (dir_ / "profile").string() + "' --enable-logging=stderr --v=0 ";
  const auto dom_file = dir_ / "dom.html", log_file = dir_ / "chromium.log";
  const std::string dump = "timeout 120 " + browser + flags + "--dump-dom '" + url + "' >'" + dom_file.string() +
                           "' 2>'" + log_file.string() + "'";
  ASSERT_EQ(std::system(dump.c_str()), 0) << read_text(log_file);
  const std::string dom = read_text(dom_file);
  for (const char* text : {"HSLM-A1", "HSLM-A2", "verdict FAIL", "<svg", "class=\"series\"", "class=\"limit\""})
    EXPECT_NE(dom.find(text), std::string::npos) << text;
  const std::string log = read_text(log_file);
  EXPECT_EQ(log.find("Uncaught"), std::string::npos) << log;
  EXPECT_EQ(log.find("net::ERR"), std::string::npos) << log;

  const auto shot = dir_ / "shot.png";
  const std::string screenshot = "timeout 120 " + browser + flags + "--hide-scrollbars --window-size=900,1400 " +
                                 "--screenshot='" + shot.string() + "' '" + url + "' >/dev/null 2>>'" +
                                 log_file.string() + "'";
  ASSERT_EQ(std::system(screenshot.c_str()), 0) << read_text(log_file);
  const auto png = read_png(shot.string());
  ASSERT_TRUE(png) << "not an 8-bit RGB(A) PNG: " << shot;
  ASSERT_GT(png->width, 100);
  // Non-blank: a real share of the page is drawn, and the plot colours are
  // there (the first series is #0072B2, the limit line #CC0000).
  long drawn = 0, blue = 0, red = 0;
  for (int y = 0; y < png->height; ++y)
    for (int x = 0; x < png->width; ++x) {
      const auto* p = png->pixel(x, y);
      if (p[0] < 235 || p[1] < 235 || p[2] < 235) ++drawn;
      if (std::abs(p[0] - 0x00) < 40 && std::abs(p[1] - 0x72) < 40 && std::abs(p[2] - 0xB2) < 40) ++blue;
      if (std::abs(p[0] - 0xCC) < 40 && p[1] < 60 && p[2] < 60) ++red;
    }
  const double area = static_cast<double>(png->width) * png->height;
  EXPECT_GT(drawn / area, 0.02) << "page looks blank";
  EXPECT_GT(blue, 50) << "no series drawn";
  EXPECT_GT(red, 50) << "no limit line or FAIL verdict drawn";
}

}  // namespace
}  // namespace railvsi::test

// vsi report end to end: a small study run through the real binary, its
// report written, then opened in headless Chromium (Debian's chromium).
#include <gtest/gtest.h>

#include <sqlite3.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>

#include "png_image.hpp"
#include "vsi_test_support.hpp"
#include "../support/worst_of.hpp"

namespace railvsi::test {
namespace {

nlohmann::json small_study() { return two_hslm_trains_study("report test <HSLM>"); }

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
  std::string chromium_flags() const {
    return " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run --user-data-dir='" +
           (dir_ / "profile").string() + "' --enable-logging=stderr --v=0 ";
  }
  // The DOM headless Chromium builds from a report file; its log in log_file.
  std::string chromium_dom(const std::string& browser, const std::filesystem::path& html,
                           const std::filesystem::path& log_file) const {
    const auto dom_file = dir_ / "dom.html";
    const std::string dump = "timeout 120 " + browser + chromium_flags() + "--dump-dom 'file://" + html.string() +
                             "' >'" + dom_file.string() + "' 2>'" + log_file.string() + "'";
    EXPECT_EQ(std::system(dump.c_str()), 0) << read_text(log_file);
    return read_text(dom_file);
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

// --out replaces a regular file only: a FIFO, a symbolic link or a folder
// at the path is left as it is (run as root, --out /dev/null had replaced
// the system's null device with the report), and so is a missing folder.
TEST_F(ReportTest, OutThatIsNotARegularFileIsRefusedAndLeftAlone) {
  const std::string id = submit(small_study(), true);
  const auto fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto target = dir_ / "target.html";
  { std::ofstream(target) << "kept"; }
  const auto link = dir_ / "link.html";
  std::filesystem::create_symlink(target, link);
  std::filesystem::create_directory(dir_ / "folder.html");
  for (const char* name : {"pipe", "link.html", "folder.html"}) {
    const VsiRun r = report(id, name);
    EXPECT_EQ(r.exit_code, 2) << name << r.err;
    EXPECT_NE(r.err.find("exists and is not a regular file"), std::string::npos) << r.err;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(read_text(target), "kept");
  const VsiRun missing = report(id, "no-such-folder/r.html");
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_NE(missing.err.find("does not exist"), std::string::npos) << missing.err;
  // A regular file is replaced, as before.
  ASSERT_EQ(report(id, "target.html").exit_code, 0);
  EXPECT_NE(read_text(target).find("<html"), std::string::npos);
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
  const std::string flags = chromium_flags();
  const auto log_file = dir_ / "chromium.log";
  const std::string dom = chromium_dom(browser, dir_ / "report.html", log_file);
  ASSERT_FALSE(HasFailure());
  for (const char* text : {"HSLM-A1", "HSLM-A2", "verdict FAIL", "<svg", "class=\"series\"", "class=\"limit\""})
    EXPECT_NE(dom.find(text), std::string::npos) << text;
  const std::string log = read_text(log_file);
  EXPECT_EQ(log.find("Uncaught"), std::string::npos) << log;
  EXPECT_EQ(log.find("net::ERR"), std::string::npos) << log;

  const auto shot = dir_ / "shot.png";
  // 3200 px tall: below the title block and contents, the summary and the
  // first check's plot.
  const std::string screenshot = "timeout 120 " + browser + flags + "--hide-scrollbars --window-size=900,3200 " +
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

// The price rows vsi stored, read with SQLite itself.
struct StoredRow {
  std::string job, quantity, rung, status, title;
  double dt_s = 0.0, cpu_s = 0.0;
  std::optional<double> error;
  bool reference = false;
};

std::vector<StoredRow> stored_price_rows(const std::filesystem::path& db) {
  sqlite3* raw = nullptr;
  EXPECT_EQ(sqlite3_open_v2(db.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  const std::unique_ptr<sqlite3, int (*)(sqlite3*)> handle(raw, sqlite3_close);
  sqlite3_stmt* st = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(raw,
                               "SELECT p.job_id, p.quantity, p.model || ' / ' || p.structure || ' / ' || "
                               "p.contact_law, p.status, p.dt_s, p.cpu_s, p.error, p.reference, j.train, "
                               "j.speed_kmh, j.irregularity FROM price_rows p JOIN jobs j ON j.id = p.job_id",
                               -1, &st, nullptr),
            SQLITE_OK)
      << sqlite3_errmsg(raw);
  std::vector<StoredRow> rows;
  const auto text = [&](int c) { return std::string(reinterpret_cast<const char*>(sqlite3_column_text(st, c))); };
  while (sqlite3_step(st) == SQLITE_ROW) {
    StoredRow r;
    r.job = text(0);
    r.quantity = text(1);
    r.rung = text(2);
    r.status = text(3);
    r.dt_s = sqlite3_column_double(st, 4);
    r.cpu_s = sqlite3_column_double(st, 5);
    if (sqlite3_column_type(st, 6) != SQLITE_NULL) r.error = sqlite3_column_double(st, 6);
    r.reference = sqlite3_column_int(st, 7) != 0;
    std::ostringstream title;
    title << r.quantity << ": " << text(8) << " at " << sqlite3_column_double(st, 9) << " km/h, " << text(10);
    r.title = title.str();
    rows.push_back(r);
  }
  sqlite3_finalize(st);
  return rows;
}

TEST_F(ReportTest, AccuracyPriceChartHasOnePointPerStoredRunAtItsLogCoordinates) {
  const std::string id = submit(small_study(), true);
  // Before vsi price: one line saying how to get the chart.
  ASSERT_EQ(report(id, "before.html", "--no-histories").exit_code, 0);
  const std::string before = read_text(dir_ / "before.html");
  EXPECT_NE(before.find("No accuracy-price chart: run vsi price --db F --study " + id.substr(0, 12)), std::string::npos);
  EXPECT_EQ(before.find("price-chart"), std::string::npos);

  const VsiRun price = vsi("price --db '" + db().string() + "' --study " + id + " --format json --threads 2");
  ASSERT_EQ(price.exit_code, 0) << price.err;
  const nlohmann::json priced = nlohmann::json::parse(price.out);
  const std::vector<StoredRow> rows = stored_price_rows(db());
  // Every run of every priced job, once per priced quantity (7), as vsi price printed it.
  std::size_t runs = 0;
  for (const auto& job : priced.at("jobs")) {
    runs += job.at("price").at("rows").size();
    for (const auto& run : job.at("price").at("rows"))
      for (const auto& [q, e] : run.at("errors").items()) {
        const auto it = std::find_if(rows.begin(), rows.end(), [&](const StoredRow& r) {
          return r.job == job.at("job") && r.quantity == q && r.dt_s == run.at("dt_s").get<double>() &&
                 r.rung == run.at("model").get<std::string>() + " / " + run.at("structure").get<std::string>() +
                               " / " + run.at("contact_law").get<std::string>();
        });
        ASSERT_NE(it, rows.end()) << q;
        EXPECT_EQ(it->cpu_s, run.at("cpu_s").get<double>());
        EXPECT_EQ(it->error.has_value(), !e.is_null()) << q;
        if (it->error) {
          EXPECT_EQ(*it->error, e.get<double>()) << q;
        }
      }
  }
  ASSERT_GT(runs, 0u);
  EXPECT_EQ(rows.size(), 7 * runs);

  ASSERT_EQ(report(id, "report.html", "--no-histories").exit_code, 0);
  const std::string html = read_text(dir_ / "report.html");
  // The charted rows: ok runs with an error, by chart.
  std::map<std::string, std::vector<const StoredRow*>> charts;
  for (const StoredRow& r : rows)
    if (r.status == "ok" && r.error && r.cpu_s > 0.0) charts[r.title].push_back(&r);
  ASSERT_FALSE(charts.empty());
  const std::regex point_re(
      "<circle class=\"price-point( pareto)?\" data-rung=\"([^\"]*)\" data-dt-s=\"([^\"]*)\" "
      "cx=\"([^\"]*)\" cy=\"([^\"]*)\"");
  std::size_t drawn = 0, references = 0;
  for (const auto& [title, group] : charts) {
    SCOPED_TRACE(title);
    const auto at = html.find("class=\"plot price-chart\" width=\"680\" height=\"320\" viewBox=\"0 0 680 320\" "
                              "role=\"img\" aria-label=\"" + title + "\"");
    ASSERT_NE(at, std::string::npos);
    const std::string svg = html.substr(at, html.find("</svg>", at) - at);
    // The log mapping, recomputed: whole decades around the CPU times; the
    // error axis from max(1e-6, the decade below the smallest non-zero
    // |error|) to the decade above max(|error|, 5 %).
    double cpu_lo = INFINITY, cpu_hi = 0.0, err_lo = INFINITY, err_hi = 0.05;
    for (const StoredRow* r : group) {
      cpu_lo = std::min(cpu_lo, r->cpu_s);
      cpu_hi = railvsi::testing::worst_of(cpu_hi, r->cpu_s);
      if (*r->error != 0.0) err_lo = std::min(err_lo, std::abs(*r->error));
      err_hi = railvsi::testing::worst_of(err_hi, std::abs(*r->error));
    }
    const double x0 = std::floor(std::log10(cpu_lo));
    const double x1 = std::max(std::ceil(std::log10(cpu_hi)), x0 + 1);
    const double y0 = std::isfinite(err_lo) ? std::max(-6.0, std::floor(std::log10(err_lo))) : -6.0;
    const double y1 = std::max(std::ceil(std::log10(err_hi)), y0 + 1);
    const double left = 70, width = 680 - 70 - 215, top = 30, height = 320 - 30 - 45;
    std::size_t points = 0;
    for (std::sregex_iterator m(svg.begin(), svg.end(), point_re), end; m != end; ++m) {
      ++points;
      const std::string rung = (*m)[2];
      const double dt = std::stod((*m)[3]);
      const auto row = std::find_if(group.begin(), group.end(),
                                    [&](const StoredRow* r) { return r->rung == rung && r->dt_s == dt; });
      ASSERT_NE(row, group.end()) << rung << " " << dt;
      const double e = std::max(std::abs(*(*row)->error), std::pow(10.0, y0));
      const double cx = left + (std::log10((*row)->cpu_s) - x0) / (x1 - x0) * width;
      const double cy = top + height - (std::log10(e) - y0) / (y1 - y0) * height;
      // The SVG prints two decimals: 0.005 px of rounding.
      EXPECT_NEAR(std::stod((*m)[4]), cx, 0.0051) << rung << " " << dt;
      EXPECT_NEAR(std::stod((*m)[5]), cy, 0.0051) << rung << " " << dt;
    }
    EXPECT_EQ(points, group.size());
    drawn += points;
    // The reference run marked, the bands drawn.
    const bool has_reference =
        std::any_of(group.begin(), group.end(), [](const StoredRow* r) { return r->reference; });
    EXPECT_EQ(svg.find("class=\"reference\"") != std::string::npos, has_reference);
    references += has_reference ? 1 : 0;
    EXPECT_NE(svg.find("data-band=\"1 %\""), std::string::npos);
    EXPECT_NE(svg.find("data-band=\"5 %\""), std::string::npos);
    EXPECT_NE(svg.find("class=\"pareto-front\""), std::string::npos);
  }
  EXPECT_GT(references, 0u);
  // No point in the report that is not a stored row.
  std::size_t all_points = 0;
  for (std::sregex_iterator m(html.begin(), html.end(), point_re), end; m != end; ++m) ++all_points;
  EXPECT_EQ(all_points, drawn);

  // And it renders in headless Chromium.
  const std::string browser = chromium();
  ASSERT_FALSE(browser.empty()) << "Debian's chromium is not installed (tests/setup installs it)";
  const auto log_file = dir_ / "chromium.log";
  const std::string dom = chromium_dom(browser, dir_ / "report.html", log_file);
  EXPECT_NE(dom.find("price-point"), std::string::npos);
  EXPECT_NE(dom.find("Accuracy price"), std::string::npos);
  EXPECT_EQ(read_text(log_file).find("Uncaught"), std::string::npos);
}

}  // namespace
}  // namespace railvsi::test

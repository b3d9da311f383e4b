#include "cli/report_pdf.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "report/report_sections.hpp"

namespace railvsi::cli {
namespace fs = std::filesystem;
namespace {

// A print of a report took 2 to 10 s on the 2-core CI machine; a hung
// browser is stopped long before a user would give up.
constexpr int kPrintTimeoutS = 180;
// The numbers settle on the second pass unless filling them in moves a
// heading (a long contents pushed onto another page); a third pass then.
constexpr int kMaxPasses = 4;

std::optional<fs::path> on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const fs::path p = fs::path(dir) / name;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return std::nullopt;
}

std::optional<fs::path> chromium() {
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"})
    if (auto p = on_path(name)) return p;
  return std::nullopt;
}

// Runs argv (no shell) in its own process group, its output to `log`;
// killed with its children after timeout_s. Throws when it does not exit 0.
void run(const std::vector<std::string>& argv, const fs::path& log, int timeout_s) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv[0]);
  if (pid == 0) {
    ::setpgid(0, 0);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      throw std::runtime_error(fmt::format("{} did not finish within {} s", argv[0], timeout_s));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  // The browser's helpers may outlive it: none is left behind.
  ::kill(-pid, SIGKILL);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("{} failed (exit {})", argv[0], WIFEXITED(status) ? WEXITSTATUS(status) : -1));
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Text with every run of white space one blank, trimmed.
std::string squeezed(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool space = c == ' ' || c == '\t' || c == '\r';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out += space ? ' ' : c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// The pages of a PDF as pdftotext reads them (a form feed between pages).
std::vector<std::string> page_texts(const fs::path& pdftotext, const fs::path& pdf, const fs::path& dir) {
  const fs::path txt = dir / "report.txt";
  run({pdftotext.string(), pdf.string(), txt.string()}, dir / "pdftotext.log", kPrintTimeoutS);
  std::vector<std::string> pages;
  std::stringstream all(read_all(txt));
  for (std::string page; std::getline(all, page, '\f');) pages.push_back(page);
  while (!pages.empty() && squeezed(pages.back()).empty()) pages.pop_back();
  return pages;
}

// Whether a line of the page is the heading (its whole line).
bool has_heading(const std::string& page, const std::string& title) {
  std::stringstream lines(page);
  for (std::string line; std::getline(lines, line);)
    if (squeezed(line) == title) return true;
  return false;
}

// The page (1-based) of each entry's heading: after the contents' own page,
// in the contents' order.
std::map<std::string, int> heading_pages(const std::vector<std::string>& pages,
                                         const std::vector<std::pair<std::string, std::string>>& entries) {
  std::size_t from = 0;
  while (from < pages.size() && !has_heading(pages[from], "Contents")) ++from;
  if (from == pages.size()) throw std::runtime_error("the printed report has no page with its contents");
  ++from;
  std::map<std::string, int> found;
  for (const auto& [id, title] : entries) {
    const std::string want = squeezed(title);
    std::size_t p = from;
    while (p < pages.size() && !has_heading(pages[p], want)) ++p;
    if (p == pages.size()) throw std::runtime_error("the heading \"" + title + "\" is on no printed page");
    found[id] = static_cast<int>(p) + 1;
    from = p;
  }
  return found;
}

}  // namespace

std::optional<std::string> pdf_tools_missing() {
  if (!chromium())
    return std::string("--pdf prints with headless Chromium: none found on PATH (chromium, chromium-browser or "
                       "google-chrome); install it (Debian: apt-get install chromium) or write the HTML with --out "
                       "and print it from a browser");
  if (!on_path("pdftotext"))
    return std::string("--pdf finds the contents' page numbers with pdftotext: not found on PATH; install "
                       "poppler-utils");
  return std::nullopt;
}

PdfPrint print_report_pdf(const std::string& html) {
  const fs::path browser = *chromium(), pdftotext = *on_path("pdftotext");
  std::string tmpl = (fs::temp_directory_path() / "vsi-report-pdf-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot make a temporary folder to print in");
  const fs::path dir = tmpl;
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{dir};
  const auto entries = contents_entries(html);
  PdfPrint out;
  std::map<std::string, int> printed;  // the numbers in the contents of the last print
  for (out.passes = 1; out.passes <= kMaxPasses; ++out.passes) {
    const fs::path page = dir / "report.html", pdf = dir / "report.pdf";
    std::ofstream(page, std::ios::binary) << with_contents_pages(html, printed);
    run({browser.string(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
         "--user-data-dir=" + (dir / "profile").string(), "--no-pdf-header-footer", "--print-to-pdf=" + pdf.string(),
         "file://" + page.string()},
        dir / "chromium.log", kPrintTimeoutS);
    const std::vector<std::string> pages = page_texts(pdftotext, pdf, dir);
    if (pages.empty()) throw std::runtime_error("Chromium printed an empty PDF");
    out.page_count = static_cast<int>(pages.size());
    out.pdf = read_all(pdf);
    if (entries.empty()) return out;  // no contents to number
    const std::map<std::string, int> found = heading_pages(pages, entries);
    if (found == printed) {
      out.pages = found;
      return out;
    }
    printed = found;
  }
  throw std::runtime_error(fmt::format("the contents' page numbers did not settle in {} prints", kMaxPasses));
}

}  // namespace railvsi::cli

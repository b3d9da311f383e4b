#pragma once
// `vsi report --pdf FILE`: the HTML report printed to an A4 PDF by headless
// Chromium, in two passes: printed once, each contents entry's heading found
// on its page (pdftotext of poppler-utils), the page numbers written into the
// contents and printed again, until the numbers found are the ones printed.
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace railvsi::cli {

struct PdfPrint {
  std::string pdf;                        // the printed document
  std::map<std::string, int> pages;       // section id -> page of its heading
  int page_count = 0;
  int passes = 0;
};

// What is missing to print (Chromium, pdftotext), or nullopt.
std::optional<std::string> pdf_tools_missing();

// Throws std::runtime_error naming the step that failed (a print that fails
// or hangs past its timeout, a heading not found, numbers that never settle).
PdfPrint print_report_pdf(const std::string& html);

}  // namespace railvsi::cli

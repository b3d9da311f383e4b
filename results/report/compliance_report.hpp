#pragma once
// The compliance report of a study as one self-contained HTML file: inline
// CSS and SVG, no script, nothing from the network, laid out for A4. This
// file only renders; what goes in (checks, plots, histories, model and
// inputs) is gathered by the study service from its store.
#include <string>
#include <vector>

#include "compliance/check_verdict.hpp"
#include "report/line_plot.hpp"
#include "report/price_chart.hpp"

namespace railvsi {

struct ReportRow {
  std::string key, value;
};

// One figure with a caption.
struct ReportFigure {
  LinePlot plot;
  std::string caption;
};

// The re-simulated histories of one governing case.
struct GoverningCase {
  std::string heading;  // e.g. "deck acceleration: HSLM-A3 at 410 km/h, none"
  std::string status;   // engine status of the re-run
  std::vector<ReportFigure> figures;
};

// Jobs that share one rung and time step (with the reason for both).
struct RungGroup {
  std::string rung;     // e.g. "moving forces, FE (cholmod), HHT alpha -0.05"
  std::string dt;       // e.g. "0.0005 s: code frequency ..."
  int jobs = 0;
};

struct JobIssue {
  std::string job;      // train, speed, profile
  std::string state;    // job state and engine status
  std::string detail;   // error text or warnings
};

struct LibraryTrain {
  std::string name;
  std::string source;   // the train file's source/description text
};

struct PriceFigure {
  PriceChart chart;
  std::string caption;
};

struct ComplianceReport {
  std::string study_name, study_id, study_file;
  std::string version, date;  // vsi version; the date line is the only non-deterministic text
  std::vector<CheckResult> checks;
  double accuracy_tolerance = 0.01;  // the study's accuracy.tolerance: a larger error estimate is flagged
  Verdict overall = Verdict::kNotEvaluated;
  std::vector<ReportFigure> check_figures;
  std::vector<GoverningCase> governing_cases;
  std::vector<ReportRow> model;          // structure, f0, f3, cut-off, damping ...
  std::vector<RungGroup> rungs;
  std::vector<JobIssue> issues;           // failed, cancelled, unfinished jobs; warnings
  std::vector<PriceFigure> price_charts;  // vsi price --db of the study, when it was run
  std::string price_note;                 // what the charts show, or how to get them
  std::vector<std::string> notes;         // e.g. checks not evaluated and why
  std::string study_document;             // canonical JSON, pretty-printed
  std::vector<LibraryTrain> trains;
};

std::string render_html(const ComplianceReport& report);

}  // namespace railvsi

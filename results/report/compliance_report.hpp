#pragma once
// The compliance report of a study as one self-contained HTML file: inline
// CSS and SVG, no script, nothing from the network, laid out for A4. This
// file only renders; what goes in (checks, plots, histories, model and
// inputs) is gathered by the study service from its store.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compliance/check_verdict.hpp"
#include "report/line_plot.hpp"
#include "report/price_chart.hpp"

namespace railvsi {

struct ReportRow {
  std::string key, value;
};

// What a governing-case figure shows of its stored job: the stored value
// and the peak of the plotted series over the samples the envelope counted
// (window_s), which must agree (vsi report --format json carries both).
struct FigureData {
  std::string quantity;  // envelope quantity, e.g. "deck_acceleration_mps2"
  std::string location;  // output point, wheel or car body
  std::string job;
  std::optional<double> stored_value;
  double plotted_peak = 0.0;
  double min = 0.0, max = 0.0;  // of the plotted series inside window_s, in SI units
  std::pair<double, double> window_s{0.0, 0.0};
  std::optional<bool> unilateral;  // contact forces: the run's contact law was unilateral
};

// One figure with a caption.
struct ReportFigure {
  LinePlot plot;
  std::string caption;
  std::optional<FigureData> data;  // governing-case figures
  std::string check;               // the check id of a plot against speed ("" for another quantity)
};

// The title block: what the report is of and who signs it.
struct TitleBlock {
  std::string project;    // the study's "project", else its name
  std::string structure;  // one line: generator, spans, deck
  std::string author;     // the study's "author"; empty: a field to fill in
};

// phi'dyn of one load effect (EN 1991-2 6.4.6.5): the largest dynamic value
// of a train's jobs against its static value.
struct PhiDynRow {
  std::string train, quantity, location, unit;
  double static_value = 0.0;  // in `unit`
  std::optional<double> dynamic_value;
  double speed_kmh = 0.0;
  std::optional<double> phi_dyn;
};

// A structure mode of the lowest ones found (deck_frequencies).
struct ModeRow {
  int number = 0;
  double frequency_hz = 0.0;
  std::string role;  // "f0", "f3", or ""
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
  TitleBlock title;
  std::vector<PhiDynRow> phi_dyn;
  // phi'dyn against speed, one figure per load effect (deflection, moment,
  // shear), one line per train: at each speed the largest over the locations.
  std::vector<ReportFigure> phi_dyn_figures;
  std::vector<ModeRow> modes;
  std::optional<ReportFigure> mode_shapes;  // the deck's, up to the code cut-off
  std::string modes_note;               // which modes the runs used
  std::vector<ReportFigure> response_figures;  // stored quantities without a check, against speed
  std::vector<std::string> unverified;  // one line per code value not confirmed in the standard's text
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

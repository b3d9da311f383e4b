#pragma once
// The figures of one governing case: histories of a run that reproduces the
// stored job (scheduler's run_planned: its rung, dt, contact law and
// escalation), each figure with the stored value it shows and the peak of
// its plotted series taken as the job's envelope took it, over the same
// samples. A figure whose plotted peak is not its stored value shows a
// different run: the report says so rather than plot it silently.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "report/compliance_report.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

// The stored envelope value of a quantity at a location (output point,
// wheel; "" for the whole job), nullopt when the job stored none.
using StoredEnvelope = std::function<std::optional<double>(const std::string& quantity, const std::string& location)>;

struct GoverningRun {
  const Scene* scene = nullptr;  // the job's stored scene
  const Result* result = nullptr;  // run_planned of it, history_stride 1
  std::string job;                 // job id
  double cutoff_hz = 0.0;          // the job's code cut-off
  // The quantity of the check the case governs: its point or wheel is shown.
  std::string check_quantity;
};

// Deck displacement and filtered acceleration at the governing point, the
// contact force of the most unloaded wheel (inside its evaluation window
// only) and the acceleration of the car body with the largest value.
std::vector<ReportFigure> governing_figures(const GoverningRun& run, const StoredEnvelope& stored);

}  // namespace railvsi

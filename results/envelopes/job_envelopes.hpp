#pragma once
// The envelopes of one job: what the
// result store keeps of a run. Every value is finite or absent: an absent
// value (std::nullopt) is "no value" in the store, never a number. A value
// is absent when it does not apply (wheel values of moving forces, a wheel
// never inside the evaluation window), when the histories cannot give it
// (the filtered acceleration needs every step), or when the run produced a
// non-finite number; the last also turns status "ok" into "diverged" and
// is named in notes.
//
// Deterministic: the same Result gives the same bits (wall_s and setup_s
// are measurements, not envelope values).
#include <optional>
#include <string>
#include <vector>

#include "simulation/result.hpp"

namespace railvsi {

struct PointEnvelope {
  std::string name;
  double x_m = 0.0;
  std::optional<double> max_abs_displacement_m;
  // After code_low_pass (EN 1990 A2.4.4.2); absent when the histories are
  // not sampled at every step.
  std::optional<double> max_abs_acceleration_mps2;
  std::optional<double> max_abs_acceleration_unfiltered_mps2;
  // Beam decks only (PointSummary); absent otherwise.
  std::optional<double> max_abs_bending_moment_Nm;
  std::optional<double> max_abs_shear_force_N;
};

// Per support of a beam deck (SupportSummary).
struct SupportEnvelope {
  std::string name;
  double x_m = 0.0;
  std::optional<double> max_reaction_N;
  std::optional<double> max_abs_rotation_rad;
};

// Wheels inside the evaluation window only (WheelSummary::evaluated); the
// others keep their name and static load with the other values absent.
struct WheelEnvelope {
  std::string name;
  bool evaluated = false;
  std::optional<double> static_load_N;
  std::optional<double> min_force_N;
  std::optional<double> unloading_ratio;  // (Q0 - Qmin)/Q0, 1 = contact lost
  std::optional<double> contact_loss_s;   // total time without contact
};

// A job's stored values: the run's summary values, absent where there is
// none (std::nullopt, not the summary's 0), plus the filtered deck
// acceleration; and the run's record as its summary has it (dt_s: the
// envelopes').
struct JobEnvelopes : RunRecord {
  std::string status = "ok";  // Status::name() of the run, or "diverged" for a non-finite value
  std::string message;
  std::vector<std::string> notes;  // values left out and why

  // Deck, per output point and over all points.
  std::vector<PointEnvelope> points;
  std::optional<double> max_abs_displacement_m;
  std::optional<double> max_abs_acceleration_mps2;  // filtered
  std::optional<double> max_abs_acceleration_unfiltered_mps2;
  double cutoff_hz = 0.0;  // code frequency max(30 Hz, 1.5 f0, f3) used
  std::string filter;      // code_filter_description()

  // Deck twist over 3 m between the track's two rail lines, in mm (the
  // unit of EN 1990 A2.4.4.2.2); applicable only with two rail lines.
  bool deck_twist_applicable = false;
  std::optional<double> max_abs_deck_twist_mm_per_3m;

  // Supports of a beam deck (empty otherwise; notes say why).
  std::vector<SupportEnvelope> supports;

  // Wheels (empty for moving forces) and over the evaluated wheels.
  std::vector<WheelEnvelope> wheels;
  std::optional<double> max_unloading_ratio;
  std::optional<double> max_contact_loss_s;  // the longest of any wheel
  std::optional<double> min_contact_force_N;

  // Car bodies inside the evaluation window (absent for moving forces).
  std::optional<double> max_abs_carbody_acceleration_mps2;

  bool ok() const { return status == "ok"; }
};

// history_stride is the AnalysisOptions::history_stride the run used. The
// filter needs the acceleration at every step: decimated histories alias
// everything above 1/(2 dt stride) into the band the filter keeps, so with
// stride > 1 the filtered values are absent (and a note says so) rather
// than quietly wrong. The displacement and unfiltered acceleration come
// from the run's summary, which sees every step whatever the stride.
// cutoff_hz: code_cutoff_hz(f0, f3) of the structure.
JobEnvelopes compute_envelopes(const Result& result, double dt_s, int history_stride, double cutoff_hz);

// For a run that filters its own deck acceleration (the modal sweep keeps
// every step in a workspace, not in histories): (*filtered_max)[p] is
// CodeFilter::max_abs_filtered of output point p's acceleration; null when
// it could not be computed, named in the notes with `obstacle`.
JobEnvelopes compute_envelopes(const Status& status, const RunSummary& summary, double dt_s, double cutoff_hz,
                               const std::vector<double>* filtered_max, const std::string& obstacle = "");

}  // namespace railvsi

#pragma once
// Everything one run needs, already validated: the immutable models and the
// options. Built by io/scene_loader from a JSON document or directly in code.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "integration/hht.hpp"
#include "model/irregularity.hpp"
#include "model/structure_model.hpp"
#include "model/train.hpp"
#include "solver/structure_backend.hpp"

namespace railvsi {

enum class SolverPath { kCondensed, kReference };

struct AnalysisOptions {
  double dt_s = 2.5e-4;
  HhtParameters hht = HhtParameters::from_alpha(-0.05);
  SolverPath solver = SolverPath::kCondensed;
  // The structure: finite elements, or its modes (modal_modes of them when
  // > 0, else all up to modal_cutoff_hz; structure_backend.hpp).
  StructureBackend structure_backend = StructureBackend::kFiniteElements;
  int modal_modes = 0;
  double modal_cutoff_hz = 0.0;
  // Hybrid: which modes of the bridge join its constraint modes.
  BridgeModes hybrid_bridge_modes = BridgeModes::kFreeInterface;
  // Modal with vehicles: the dropped modes' static flexibility at the rails
  // (StructureOperatorOptions::modal_static_correction).
  bool modal_static_correction = true;
  ContactOptions contact;
  int max_newton_iterations = 50;
  // Newton stops when |residual| / |static wheel loads| <= tol (eq. 25).
  double newton_tolerance = 1e-10;
  // Simulated time; by default until the last axle has left the modelled
  // track (past the rail ends, and at least evaluation_margin_m past the
  // bridge), then the free vibration, plus extra_time_s.
  std::optional<double> duration_s;
  // Free vibration after the last axle has left: given, or
  // max(free_vibration_min_s, free_vibration_periods / structure_f0_hz) (the
  // minimum alone while f0 is not known). A run cut short of it missed the
  // free-vibration maximum off resonance (HSLM-A1 at 343 km/h on a 25 m,
  // 3.55 Hz span: -11.6 % with 0.105 s after the last axle).
  std::optional<double> free_vibration_s;
  double free_vibration_min_s = 1.0;
  double free_vibration_periods = 3.0;
  // The structure's first bending frequency when the caller knows it (a
  // study and vsi simulate compute it); 0: not known. Not part of a scene
  // document: a study writes free_vibration_s into each job's scene.
  double structure_f0_hz = 0.0;
  // Wheel and car-body envelopes count while the wheel (any wheel of the
  // vehicle) is within this distance of the bridge: transients where wheels
  // leave the modelled track are not bridge results.
  double evaluation_margin_m = 10.0;
  double extra_time_s = 0.0;
  // Store every n-th step in the histories.
  int history_stride = 1;
  // Runs beyond the size limits (RunLimits) are refused unless this is set
  // (vsi simulate --allow-large). Not part of a scene document.
  bool allow_large_run = false;
};

// Which rung of the fidelity ladder runs a scene (schemas: "fidelity",
// "accuracy", "asks"). The rung itself is planned above the engine
// (results/planning/effects_planner); the engine runs what it is given.
struct FidelityRequest {
  enum class Mode { kAsGiven, kAuto, kPinned };
  Mode mode = Mode::kAsGiven;  // kAsGiven: FE with the analysis options (no "fidelity" key)
  // kPinned: "moving_forces" | "interaction", "modal" | "fe"; the contact
  // law and unilaterality are applied to AnalysisOptions::contact.
  std::string model, structure;
  std::optional<double> modal_cutoff_hz;
  std::optional<double> escalate_below_fraction;
  std::optional<double> escalation_dt_factor;  // the repeated run's dt / the scene's; absent: 1
  std::vector<std::string> reasons;
  double tolerance = 0.01;
  // kAuto: what the run must answer; absent: what the train can give.
  std::optional<std::vector<std::string>> asks;
  // Whether the run must give section forces (absent asks: yes). The
  // modal rungs skip them otherwise; the FE rungs compute them anyway.
  bool asks_section_forces() const {
    return !asks || std::find(asks->begin(), asks->end(), "section_forces") != asks->end();
  }
};

struct Scene {
  std::shared_ptr<const StructureModel> structure;
  Train train;
  double speed_mps = 0.0;
  std::shared_ptr<const Irregularity> irregularity;  // null: perfect track
  AnalysisOptions analysis;
  // x of the train's first axle at t = 0; default_start_x_m() when absent.
  std::optional<double> start_x_m;
  FidelityRequest fidelity;
};

// The whole train on the modelled track when the approach is long enough
// (a true static equilibrium, no entry transient), the first axle at the
// bridge start otherwise.
double default_start_x_m(const Scene& scene);
// [start, end] of the bridge along rail line 0.
std::pair<double, double> bridge_extent_m(const StructureModel& structure);

}  // namespace railvsi

#pragma once
// What a run returns: a status, a summary, and the time histories at the
// requested points. A failed run keeps what it computed up to the failure
// for diagnosis, but its status says it is not a result.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/status.hpp"

namespace railvsi {

struct Histories {
  std::vector<double> t_s;
  std::vector<std::string> point_names;
  std::vector<std::vector<double>> deck_displacement_m;    // [point][sample]
  std::vector<std::vector<double>> deck_acceleration_mps2;  // [point][sample]
  std::vector<std::string> wheel_names;                    // "v<vehicle>_w<wheel>"
  std::vector<std::vector<double>> contact_force_N;        // [wheel][sample]
  std::vector<std::string> body_names;                     // "v<vehicle>_body"
  std::vector<std::vector<double>> carbody_acceleration_mps2;  // [body][sample]
};

struct PointSummary {
  std::string name;
  double x_m = 0.0;
  double max_abs_displacement_m = 0.0;
  double max_abs_acceleration_mps2 = 0.0;
  // Beam decks only (simulation/section_forms.hpp); absent otherwise.
  std::optional<double> max_abs_bending_moment_Nm;
  std::optional<double> max_abs_shear_force_N;  // the larger of the two sides
};

// Per support of a beam deck: traffic reaction (upward) and deck end rotation.
struct SupportSummary {
  std::string name;
  double x_m = 0.0;
  double max_reaction_N = 0.0;
  double max_abs_rotation_rad = 0.0;
};

// Per wheel, over the evaluation window (see AnalysisOptions).
struct WheelSummary {
  std::string name;  // as in Histories::wheel_names
  double static_load_N = 0.0;
  double min_force_N = 0.0;
  double unloading_ratio = 0.0;  // (Q0 - Qmin)/Q0
  double contact_loss_s = 0.0;   // total time without contact
  bool evaluated = false;        // false: never inside the evaluation window
};

// Which model a run actually used: recorded with every result.
struct FidelityRecord {
  std::string model;          // load_model_name(): "moving_forces", "interaction"
  std::string contact_law;    // "none", "rigid", "linear-hertz", "hertz"
  bool unilateral = false;
  std::string solver_path;    // "condensed", "reference"
  std::string structure_backend;
  int structure_dofs = 0;
  int vehicle_dofs = 0;
  int contacts = 0;
  double hht_alpha = 0.0, hht_beta = 0.0, hht_gamma = 0.0;
  // The rung of the fidelity ladder ("moving_forces/modal", "interaction/fe",
  // ...), who chose it ("planner", "pinned"; empty: the scene's analysis as
  // given), and why: what the rung leaves out and why that is safe here.
  std::string rung;
  std::string chosen_by;
  double dt_s = 0.0;
  int modes = 0;                 // modal rungs: modes kept, all up to modal_cutoff_hz
  double modal_cutoff_hz = 0.0;
  // Modal interaction: the dropped modes' static flexibility at the rails
  // was added to the contact's (ModalOperatorOptions::static_correction).
  // Modal moving forces: their static response was added at the output
  // points (DeckOutputCorrection::kStatic).
  bool static_correction = false;
  std::vector<std::string> reasons;
  struct Ignored {
    std::string what, why;
  };
  std::vector<Ignored> ignores;
  std::string escalation;  // why the run was repeated on a fuller rung; empty when it was not
};

// Something a user must know about a run that still has a result (status ok)
// or that explains a non-ok status. `code` is stable (documented in the
// README); the optional fields locate it.
struct RunWarning {
  std::string code;     // e.g. "dt_above_policy", "contact_chatter"
  std::string message;  // one sentence for a person
  std::optional<double> t_s;     // when it was first seen
  std::optional<int> wheel;      // index into RunSummary::wheels
  std::optional<double> factor;  // e.g. dt over the policy's dt
};

// section_forces_note of a modal run whose asks leave section forces out.
inline constexpr const char* kSectionForcesNotAsked = "section forces were not asked (asks without \"section_forces\")";

// How a run went, beside its values: its steps, Newton work, times, the
// fidelity it ran at and its health. One record for the engine's summary
// and the stored envelopes, which both are one (RunSummary, JobEnvelopes).
struct RunRecord {
  long steps = 0;
  double dt_s = 0.0;
  long newton_iterations = 0;
  int max_newton_iterations_in_step = 0;
  double wall_s = 0.0;
  double setup_s = 0.0;  // factorization, flexibility, static equilibrium
  FidelityRecord fidelity;
  // Run health: warnings, and the energy balance residual (work of external
  // and contact forces against kinetic + strain + damping + HHT-dissipated
  // energy, relative); NaN when not computed.
  std::vector<RunWarning> warnings;
  double energy_residual = std::numeric_limits<double>::quiet_NaN();
};

// The run's values as the engine finds them (0 where a train of moving
// forces has no wheel or car body: summary_json prints null there), and
// its record.
struct RunSummary : RunRecord {
  std::vector<PointSummary> points;
  double max_abs_displacement_m = 0.0;
  double max_abs_acceleration_mps2 = 0.0;  // unfiltered
  // Wheels (empty train of moving forces: no wheels, values stay 0).
  double min_contact_force_N = 0.0;
  double max_unloading_ratio = 0.0;  // (Q0 - Qmin)/Q0, 1 = contact lost
  double contact_loss_s = 0.0;       // longest time any wheel spent without contact
  std::vector<double> static_wheel_load_N;
  std::vector<WheelSummary> wheels;
  double max_abs_carbody_acceleration_mps2 = 0.0;
  // Supports of a beam deck; empty with section_forces_note saying why
  // when the structure has no section forces (3D solid deck, import).
  std::vector<SupportSummary> supports;
  std::string section_forces_note;
  // Deck twist over 3 m between the track's two rail lines, max over time
  // and position (simulation/deck_twist.hpp); absent with deck_twist_note
  // saying why (a plane model: not applicable).
  std::optional<double> max_abs_deck_twist_m;
  double deck_twist_x_m = 0.0;  // start of the 3 m base where it occurs
  std::string deck_twist_note;
};

struct Result {
  Status status;
  RunSummary summary;
  Histories histories;
};

}  // namespace railvsi

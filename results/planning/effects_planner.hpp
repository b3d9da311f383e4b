#pragma once
// The effects planner: from what a study asks (the outputs and checks it
// requests), whether a track irregularity is given and whether the train is
// a load model (axle forces: HSLM, LM) or multibody vehicles, the cheapest
// rung of the fidelity ladder that answers it within the study's tolerance.
// A pure function of its input; the rules and their reasons (README "The
// effects planner"):
//   1. A load model has no vehicle: moving forces, whatever is asked (wheel
//      and car-body values have no meaning for it and stay absent; an
//      irregularity is not felt by a force).
//   2. Multibody vehicles: interaction, since their suspensions change the
//      deck response near resonance and wheel unloading, comfort and an
//      irregularity need the vehicle. Linear Hertz (bilateral) first; the
//      run is repeated with nonlinear unilateral Hertz when a contact force
//      drops below kEscalationFraction of its static load (escalation());
//      when wheel quantities are asked, below kWheelEscalationFraction and
//      at half the time step (kWheelEscalationDtFactor).
//   3. Moving forces: the structure is modal (all modes up to
//      kModalCutoffMargin x the code frequency max(30 Hz, 1.5 f0, f3) of
//      EN 1990 A2.4.4.2.1(3), exact recurrence) unless the cut-off cannot
//      be honoured: the deck frequencies or the mode count are unknown, or
//      more than kMaxModalModes modes lie below it; then FE.
//   4. Interaction: hybrid (the track in FE, the bridge in its modes up to
//      kHybridCutoffFactor x the code frequency) where the bridge has an
//      interior that the modes replace (at least kHybridMinInteriorDofs
//      DOFs and kHybridMinInteriorRatio x the DOFs the track bears on) and
//      that cut-off is at most kHybridMaxCutoffHz; else FE. Never the modal structure: the track's own modes respond
//      where the wheel forces have their content (kModalInteractionNotTrusted).
#include <optional>
#include <string>
#include <vector>

#include "simulation/result.hpp"

namespace railvsi {

// The modes kept reach this multiple of the code frequency: a mode at the
// code frequency is kept whatever its discretization error (a 20 % margin
// covers the error of a coarse mesh on the third bending mode).
inline constexpr double kModalCutoffMargin = 1.2;
// Beyond this many modes the modal rung is neither cheap (the loads are
// modes x axles per step) nor quick to set up (Lanczos): FE.
inline constexpr int kMaxModalModes = 200;
// Linearized Hertz holds while the force stays near its static load: the
// Hertz tangent stiffness goes as P^(1/3), 0.79 of the static one at half
// the load, and a bilateral spring would hold a wheel that lifts off.
inline constexpr double kEscalationFraction = 0.5;
// When wheel quantities (wheel unloading, contact loss) are asked, linear
// Hertz answers only while every wheel keeps this fraction of its static
// load, and the escalated run takes kWheelEscalationDtFactor x the run's
// time step. Measured on the viaduct with ICE3 and Eurostar against the
// full model (unilateral Hertz at dt / 4; README "Is the planner safe?"):
// linearized Hertz carries a model error of its own on dQ/Q, +0.60 % at an
// unloading of 0.24 but +0.95 % at 0.34 and +0.96 % at 0.46, at the edge of
// a 1 % tolerance (within it at 0.46 only by cancelling the time-step
// error); and where a wheel unloads past half its load, unilateral Hertz at
// the policy's dt (0.25 ms, bound by the contact frequency) is off by up
// to 2.3 % on Q min and 3.2 % on the contact-loss time, some of it
// unconservative, and by less than 1 % at dt / 2. The deck and car-body
// values are within 0.4 % on either rung at dt: a study that does not ask
// wheel quantities keeps kEscalationFraction and the run's dt.
inline constexpr double kWheelEscalationFraction = 0.7;
// The hybrid structure keeps the bridge's own modes (free-interface:
// BridgeModes) up to this multiple of the code frequency. Measured on
// generated 3D decks of three 25 m spans under ICE3 at 300 km/h against FE
// at the same dt and law (tests/bench/hybrid_bench --free-interface,
// 2026-11-28): at 3 x the code frequency the deck displacement and filtered
// acceleration within 0.004 % / 0.001 % on 19,869 DOFs (110 Hz: 48 modes)
// and 0.004 % / 0.028 % at seed scale (231,825 DOFs, 45 modes); over a
// 20 mm dip -0.10 % / -0.005 % on 6,042 DOFs (113 Hz) and +0.001 % /
// -0.090 % on 19,869 DOFs, the contact-loss time equal to FE's; the wheel
// values within 0.001 %. At 2 x (75 Hz) the dip gave -0.23 % / -0.52 %.
// (The fixed-interface modes, before, needed 6 x: +0.08 % at 225 Hz over
// the dip on 6,042 DOFs, +1.8 % at 221 Hz on 19,869.)
// With a wheel's contact lost (dips of 20-30 mm, mid-span or over a pier,
// 250-350 km/h, 3,025-19,869 DOFs, 2026-11-28) the deck within 0.3 %, the
// car body 0.02 % and the contact-loss time 0.25 ms: no repeat on FE.
inline constexpr double kHybridCutoffFactor = 3.0;
// ... but not above this: the cut-off of a short stiff span (a code
// frequency of 119 Hz on two 12 m spans asks 357 Hz) keeps most of the
// deck's modes, which costs more than FE and was never measured. Above it
// interaction stays on FE.
inline constexpr double kHybridMaxCutoffHz = 250.0;
// The hybrid structure pays a dense block of (interface DOFs + modes)^2: it
// is cheaper than FE only where the modes replace a bridge interior several
// times larger than the interface (a 3D deck, an imported model), not on a
// plane viaduct whose deck DOFs all carry the track.
inline constexpr int kHybridMinInteriorDofs = 1000;
inline constexpr double kHybridMinInteriorRatio = 4.0;
inline constexpr double kWheelEscalationDtFactor = 0.5;

struct Rung {
  std::string model = "moving_forces";  // "moving_forces" | "interaction"
  std::string structure = "modal";      // "modal" | "fe" | "hybrid" (interaction)
  std::string contact_law = "none";     // "none" (moving forces), "linear-hertz", "hertz", "rigid"
  bool unilateral = false;
  std::string name() const { return model + "/" + structure; }
  // Moving forces on the modes, each stepped by the exact recurrence (the
  // batched sweep path); interaction on the modes is stepped by HHT.
  bool exact_modal() const { return model == "moving_forces" && structure == "modal"; }
};

struct StudyAsks {
  bool deck = true;              // deck acceleration / displacement
  bool wheel_unloading = false;  // dQ/Q, contact loss
  bool comfort = false;          // car-body acceleration
  // Section forces, reactions and end rotations of a beam deck: every rung
  // that has them computes them (on the modal sweep they cost about as
  // much as the deck response); not asked, the modal sweep skips them.
  bool section_forces = true;
};

struct PlannerInput {
  StudyAsks asks;
  bool irregularity = false;
  bool load_model = true;  // a train of moving forces; false: multibody vehicles
  double f0_hz = 0.0, f3_hz = 0.0;  // deck frequencies; 0 when not computed
  int modes_below_cutoff = -1;      // modes up to the modal cut-off; -1 when not counted
  // How the hybrid structure would split the structure (interaction):
  // track_dofs 0 when the structure has no track or was not looked at.
  int track_dofs = 0, interface_dofs = 0, interior_dofs = 0;
  double tolerance = 0.01;          // relative, of every governing envelope value
};

struct EffectsPlan {
  Rung rung;
  double code_frequency_hz = 0.0;  // max(30 Hz, 1.5 f0, f3)
  double modal_cutoff_hz = 0.0;    // modal rungs: kModalCutoffMargin x code frequency; hybrid: kHybridCutoffFactor x
  std::vector<std::string> reasons;
  std::vector<FidelityRecord::Ignored> ignores;
  // Linear Hertz: repeat with unilateral Hertz below this fraction of a static load,
  std::optional<double> escalate_below_fraction;
  // at this fraction of the time step (absent: the same step).
  std::optional<double> escalation_dt_factor;
};

EffectsPlan plan_effects(const PlannerInput& input);

// Why interaction never runs on the modal structure when the planner
// chooses (and a scene with a track is refused it): the errors of the modal
// interaction rung against the FE rung, from tests/verification/
// modal_structure_test.cpp and docs/method.md.
inline constexpr const char* kModalInteractionNotTrusted =
    "interaction on the modes misses the tolerance: measured against the FE structure, its filtered deck "
    "acceleration is 1.0 % off on a beam viaduct without track (9 modes to 60 Hz; 0.16 % at 18 modes), 1.8 % on a "
    "3D deck on pads (5 modes to 30 Hz) and 10 % to 84 % under a ballasted track at any cut-off (the track's own "
    "modes respond where the wheel forces have their content, and its pads and ballast dampers couple the modes), "
    "and its minimum contact force up to 10 % (docs/method.md, \"The modal structure\")";

// What a rung leaves out of the full model (FE, nonlinear unilateral Hertz)
// and why, for the run's fidelity record.
// escalate_below: the fraction below which linear Hertz is repeated as
// unilateral Hertz, if the run does so.
std::vector<FidelityRecord::Ignored> rung_ignores(const Rung& rung, bool irregularity, double modal_cutoff_hz,
                                                  std::optional<double> escalate_below = std::nullopt);

// The reason to repeat a run on unilateral Hertz: the first evaluated wheel
// whose smallest contact force fell below fraction x its static load;
// nullopt when none did. dt_factor (< 1): the repeated run's time step as a
// fraction of the run's dt_s, said in the reason.
std::optional<std::string> escalation_reason(const RunSummary& summary, double fraction,
                                             std::optional<double> dt_factor = std::nullopt);
// Interaction with nonlinear unilateral Hertz on the same structure.
Rung escalated(const Rung& rung);

// One rung up the ladder toward the full model (FE, nonlinear unilateral
// Hertz), for an error estimate (a study's accuracy.verify): the exact modal
// moving forces -> moving forces on FE; interaction on the modes -> the same
// contact law on FE; interaction on FE with linear Hertz or rigid contact ->
// nonlinear unilateral Hertz (escalated()). nullopt for the full model and
// for moving forces on FE (a load model has no vehicle to couple).
std::optional<Rung> next_rung(const Rung& rung);

// How the peaks of a modal run are taken from its samples.
enum class ModalPeaks {
  // Deck displacement and acceleration (filtered or not) alone: each peak
  // is refined between its samples (core/sampled_peak.hpp).
  // The recurrence's own error (the load is linear within a step) sets a
  // floor on both refined kinds: on S1 (25 m, f0 = 3.55 Hz, where mode 3
  // at 31.95 Hz sets the code frequency) the filtered deck acceleration of
  // HSLM-A1..A10 at 150-400 km/h against dt = 0.125 ms was -3.60 % at 8
  // samples a period and -0.75 % at 16 (2026-11-27, the S1 sweep of
  // tests/cli/s1_caldintav_sweep_test.cpp): n >= 16 sqrt(0.01 / tolerance).
  kRefined,
  // Also section forces: refined as the deck's between kinks, and
  // evaluated at every instant an axle crosses a section or support (where
  // their influence lines have a kink or a jump that no parabola follows;
  // analysis/modal_sweep.hpp). What is left is the recurrence's own error
  // (the load is linear within a step), largest on the midspan shear:
  // measured against a step 16 times shorter over HSLM-A1..A10 at 100-400
  // km/h (tests/results/section_force_peaks_test.cpp, 2026-11-27), at 8
  // samples a period of the code frequency: shear 0.82 % (15 m, 5 Hz) and
  // 0.63 % (8 m, 12 Hz), moment, reactions and end rotations <= 0.53 %;
  // at 16 samples 0.19 % and 0.15 %: about 0.52 / n^2, below the floor
  // n >= 16 sqrt(0.01 / tolerance) that the deck's acceleration needs.
  kRefinedWithSections,
  // Also the deck twist, whose peak is the largest sample.
  kSampled,
};

// Time step of the modal rung, where dt only samples the load and the
// output (the recurrence is exact for a load linear within a step): the
// smallest number n of samples a period of a harmonic at the code
// frequency for which its peak is low by at most the tolerance: 1 - cos(pi
// / n) for the largest sample (n = 23 for 1 %), 1 - cos(pi / n) (1 +
// sin^2(pi / n) / 2) when refined (n = 8 for 1 %), and when refined at least
// the recurrence's floor n >= 16 sqrt(0.01 / tolerance) (above; n = 16 for 1 %). The step is rounded down to 3
// significant digits.
double modal_time_step_s(double code_frequency_hz, double tolerance, ModalPeaks peaks);

}  // namespace railvsi

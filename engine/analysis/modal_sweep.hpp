#pragma once
// The per-run path of the modal moving-force rung, split into what every
// run of one train on one structure at one dt shares (built once: the
// modal steps, the axles sorted by offset, the mode shapes at the four DOFs
// of every rail element, contiguous) and what one speed needs (a workspace
// the caller keeps between runs, so a sweep allocates nothing per step).
// Within an element the modes under an axle are the cubic Hermite
// interpolation of its end values (as RailLine's weights). All axles move
// together, so the modal load of the whole train is a function of one
// position s, that of the first axle: between two positions where some
// axle crosses a node (or a rail end) the set of axles on the rail and
// their elements do not change, and the load is one cubic in s, the sum of
// the axles' cubics. The train's load is tabulated once per sweep as those
// cubics, and a step evaluates one cubic per mode (Horner's rule) however
// many axles are on the span; the piece only ever advances. At a
// breakpoint itself (an axle exactly on a node or a rail end) the axles
// are summed one by one, as RailLine::locate places them. A run gives the
// same bits whether it is the first of a sweep or alone.
// With section forces (a beam deck), the influence line of each section
// form rides along as one more column of the same cubics, so the exact
// static part costs what one more mode costs per axle; so do the residual
// influence line of each output point and its second derivative, for the
// static correction of the deck outputs (DeckOutputCorrection).
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/lane_code.hpp"
#include "simulation/modal_section_forces.hpp"
#include "solver/modal_basis.hpp"
#include "core/status.hpp"
#include "integration/modal_recurrence.hpp"
#include "model/train.hpp"
#include "simulation/deck_twist.hpp"
#include "simulation/result.hpp"

namespace railvsi {

// How the deck displacement and acceleration at the output points are
// formed. The kept modes alone miss the static response of the modes above
// the cut-off: under a moving axle the local deformation of a plate or of
// the track, and a share of a beam's deflection. kStatic adds it exactly
// (the mode-acceleration method, Cornwell, Craig & Johnson, Earthquake Eng.
// Struct. Dyn. 11, 1983): u_i = Phi_i q + sum over axles of F r_i(x_a), with
// r_i the output's residual influence line (ModalBasis::
// output_residual_flexibility, interpolated on the rails as the modes are),
// and its acceleration v^2 F r_i''(x_a) for axles moving at speed v.
enum class DeckOutputCorrection {
  kNone,    // Phi q and Phi q'' alone
  kStatic,  // plus the static response of the modes left out (the default)
};

// Speeds a sweep runs together, one per lane: their recurrences are
// independent, so the processor overlaps them (and the compiler may put
// them in one vector register); each lane's arithmetic is the same as
// when it runs alone, so a run gives the same bits in a group or alone.
inline constexpr int kSweepLanes = 4;

// One run of a group: first axle at x0_m at t = 0, moving at speed_mps >= 0, n_steps steps.
struct SweepLane {
  double x0_m = 0.0, speed_mps = 0.0;
  long n_steps = 0;
};

// What one run reuses from the previous one (sized on first use).
struct ModalSweepWorkspace {
  // Lane-minor: p[column * lanes + lane]. p: the modal loads,
  // then (with section forces) the static value of each form under them,
  // then (with the static correction) each output's residual displacement
  // and its second derivative in x under them.
  std::vector<double> p, q, qd, qdd;
  // The loads of a chunk of steps, evaluated before their recurrence.
  std::vector<double> chunk;
  // The section forms' values of every lane (lane-minor), and of one.
  std::vector<double> lane_values, form_values;
  // Deck displacement and acceleration at every step (n_steps + 1
  // samples), per lane and output point: the peaks are refined from them
  // (core/sampled_peak.hpp) and the code filter reads the acceleration.
  std::array<std::vector<std::vector<double>>, kSweepLanes> displacement, acceleration;
  std::vector<std::size_t> piece;  // per rail and lane: the piece of its train load the first axle is on
  std::vector<double> offset;      // per rail and lane: the first axle's distance from that piece's start
  // With section forces: the modal state at the start of a step in which
  // an axle crosses a kink of the forms (lane-minor, as q), and the train
  // load's columns on both sides of the kink.
  std::vector<double> q_start, qd_start, qdd_start;
  std::vector<double> kink_columns;
  // Each form's values over the last chunk of steps, per lane and form
  // (the chunk's samples and the two before it), and per lane where its
  // samples split at the kinks (pairs: the last sample before a kink, the
  // first after it not on it), so that a peak between two samples away
  // from a kink is refined as the deck's, chunk by chunk while the samples
  // are in cache.
  std::vector<double> form_window;
  std::array<std::vector<long>, kSweepLanes> kink_splits;
};

// The kernel's raw output for one lane. Not a second result model: every
// caller turns it into the one RunSummary by fill_modal_summary
// (modal_moving_forces.hpp) before anything above the engine sees it.
struct ModalSweepRun {
  Status status;
  long steps = 0;
  // Per output point, refined between steps (core/sampled_peak.hpp).
  std::vector<double> max_abs_displacement_m, max_abs_acceleration_mps2;
  // The section envelope when the sweep has section forces: the maxima
  // over the steps and over every instant between two steps at which an
  // axle crosses a section, a support or a rail end (a kink of the forms).
  std::optional<SectionEnvelope> sections;
  // Deck twist over 3 m (m), max over steps and bases, and the start of
  // its base; absent when the sweep's rails give no twist (twist_gauge()).
  std::optional<double> max_abs_twist_m;
  double twist_x_m = 0.0;
};

class ModalSweep {
 public:
  // rail_lines: the rails the forces bear on (shared equally); dt_s > 0.
  // sections: the section forces to evaluate every step (null: none); of
  // the same basis and rail lines.
  ModalSweep(const ModalBasis& basis, const Train& train, const std::vector<int>& rail_lines, double dt_s,
             std::shared_ptr<const ModalSectionForces> sections = nullptr,
             DeckOutputCorrection correction = DeckOutputCorrection::kStatic);

  // First axle at x0_m at t = 0, moving at speed_mps >= 0, for n_steps steps
  // from the static modal response. Keeps the deck displacement and
  // acceleration of every step in ws.displacement[0] and ws.acceleration[0];
  // fills histories (every history_stride-th step and the last) when not
  // null. The peaks at the output points are refined_max_abs of the kept
  // samples: a peak between two steps is not missed.
  ModalSweepRun run(double x0_m, double speed_mps, long n_steps, ModalSweepWorkspace& ws,
                    Histories* histories = nullptr, int history_stride = 1) const;
  // Up to kSweepLanes runs at once (no histories); run i keeps its deck
  // response in ws.displacement[i] and ws.acceleration[i]. Each gives the
  // bits run() gives.
  std::vector<ModalSweepRun> run_group(const std::vector<SweepLane>& lanes, ModalSweepWorkspace& ws,
                                       LaneCode code = LaneCode::kFastest) const;

  const ModalBasis& basis() const { return basis_; }
  int num_modes() const { return n_modes_; }
  DeckOutputCorrection correction() const { return correction_; }
  const ModalSectionForces* sections() const { return sections_.get(); }
  const DeckTwistGauge& twist_gauge() const { return twist_; }
  double dt_s() const { return dt_s_; }

 private:
  struct Rail {
    int line = 0;  // index in the structure's rails
    std::vector<double> x_m;
    double start_m = 0.0, end_m = 0.0;
    // Per element and mode, the modal load of a unit downward axle force as
    // a cubic in xi (the Hermite interpolation of the element's end
    // displacements and rotations, with the share of this rail and the
    // sign): c0 + c1 xi + c2 xi^2 + c3 xi^3, stored [element][column][4];
    // columns: the modes, then the unit static value of each section form
    // (a cubic inside an element; at its first node a load may be excluded
    // from a shear cut, which the exact evaluation handles), then with the
    // static correction the residual displacement of each output point and
    // its second derivative in x.
    std::vector<double> cubic;
    // The train's load on this rail against the first axle's position s:
    // piece i covers [breaks[i], breaks[i+1]) and holds, per column, the
    // cubic in u = s - breaks[i], in groups of kColumnGroup columns (the
    // last padded with zeros) so that one vector evaluates a group:
    // pieces[piece_index(i, column, power)].
    std::vector<double> breaks, pieces;
  };
  // Columns of the train-load table evaluated together, one vector.
  static constexpr std::size_t kColumnGroup = 4;
  std::size_t piece_index(std::size_t piece, std::size_t column, std::size_t power) const {
    return ((piece * groups_ + column / kColumnGroup) * 4 + power) * kColumnGroup + column % kColumnGroup;
  }
  // Tabulates the train's load on `rail` (its cubics built).
  void tabulate_train_load(Rail& rail) const;
  // p[column * stride] = Phi^T f for the first axle at x, then the static
  // form values; piece[r * stride]: where the last call left rail r (x
  // never decreases between calls with the same pieces).
  void modal_load(double x, double* p, std::size_t stride, std::size_t* piece, ModalSweepWorkspace& ws) const;
  // The load of `rail`'s table in piece i at u from its start, column by
  // column: p[column * stride] = (assign) or += its cubic by Horner's rule.
  void piece_load(const Rail& rail, std::size_t i, double u, double* p, std::size_t stride, bool assign) const;
  // The same for one rail, axle by axle (at a breakpoint of its table).
  void add_axle_loads(const Rail& rail, double x, double* p, std::size_t stride, ModalSweepWorkspace& ws) const;
  // The runs of one group, L lanes (lanes[i] for i < count, the rest idle).
  // Inlined into run() and into the two functions below, one for the
  // baseline processor and one for AVX2 (the same bits).
  void run_four_lanes(const SweepLane* lanes, int count, ModalSweepRun* out, ModalSweepWorkspace& ws) const;
  void run_four_lanes_avx2(const SweepLane* lanes, int count, ModalSweepRun* out, ModalSweepWorkspace& ws) const;
  template <int L>
  // code: which copy of the peaks' refinement runs (the same bits).
  void run_lanes(const SweepLane* lanes, int count, ModalSweepRun* out, ModalSweepWorkspace& ws,
                 Histories* histories, int history_stride, LaneCode code) const;

  // A run whose deck displacement at an output point exceeds u_limit_m_
  // ends unstable, as RunMonitor's rule on the FE rungs: a linear model far
  // outside its range (a stiffness given in kN, a mass in t) is no result.
  void check_plausible(ModalSweepRun& run) const;
  // The train load's columns for the first axle at s (width_ of them, +=),
  // as the limit from below (left) or from above: at a breakpoint a form's
  // influence line may have a kink or a jump (a shear cut).
  void table_columns_at(double s, bool left, double* columns) const;

  const ModalBasis& basis_;
  double u_limit_m_ = 0.0;  // max(0.1 m, bridge length / 100)
  int n_modes_ = 0;
  int width_ = 0;  // columns of the cubics: modes, section forms, corrections
  std::size_t groups_ = 0;  // of kColumnGroup columns in the train-load table
  int n_forms_ = 0;
  int n_corrected_ = 0;  // output points with the static correction (all or none)
  DeckOutputCorrection correction_ = DeckOutputCorrection::kStatic;
  double dt_s_ = 0.0;
  std::shared_ptr<const ModalSectionForces> sections_;
  // Per section form: read signed by the envelope (a support reaction);
  // forms_fold_: no form is read both signed and as |value|, so the
  // envelope can be folded from each form's maxima at the end of a run.
  std::vector<bool> form_signed_;
  bool forms_fold_ = false;
  // The twist of each base as a row over the modes (the gauge's forms
  // applied to the mode shapes at the rail DOFs): t = row . q.
  DeckTwistGauge twist_;
  DenseMatrix twist_modes_;
  double share_ = 1.0;
  std::vector<ModalStep> steps_;
  std::vector<double> inverse_omega2_;
  std::vector<double> offsets_, loads_N_;  // axles by offset
  // Positions of the first axle at which some axle stands on a section of
  // the forms, a support or a rail end, ascending: there a form's static
  // part (its influence line) has a kink or a jump, so its peak may fall
  // between two steps where no parabola through the samples follows it.
  // The sweep evaluates the forms there, the modes' state interpolated.
  std::vector<double> kinks_m_;
  std::vector<Rail> rails_;
};

}  // namespace railvsi

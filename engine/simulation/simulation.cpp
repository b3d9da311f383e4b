#include "simulation/simulation.hpp"

#include <chrono>
#include <limits>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "simulation/load_model.hpp"
#include "simulation/modal_section_forces.hpp"
#include "simulation/run_state.hpp"
#include "simulation/static_equilibrium.hpp"
#include "simulation/step_solver.hpp"
#include "solver/hybrid_operator.hpp"
#include "solver/modal_operator.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

EffectiveMatrixFactors structure_factors(const HhtCoefficients& h) {
  return {h.mass_factor(), h.damping_factor(), h.stiffness_factor()};
}

}  // namespace

double free_vibration_s(const AnalysisOptions& analysis) {
  if (analysis.free_vibration_s) return *analysis.free_vibration_s;
  // At most 10 s (f0 = 0.3 Hz): a mechanism's f0 of nearly 0 would ask for
  // days, and be refused for its length before its mechanism is named.
  const double periods_s =
      analysis.structure_f0_hz > 0.0 ? analysis.free_vibration_periods / analysis.structure_f0_hz : 0.0;
  return std::max(analysis.free_vibration_min_s, std::min(periods_s, kMaxDefaultFreeVibrationS));
}

double track_exit_m(const Scene& scene) {
  double end_m = bridge_extent_m(*scene.structure).second + scene.analysis.evaluation_margin_m;
  for (const RailLine& rail : scene.structure->rails()) end_m = std::max(end_m, rail.end_m());
  return end_m;
}

// Time simulated: until the last axle has left the modelled track, then the
// deck's free vibration, plus any extra time asked for.
double default_duration_s(const Scene& scene, double start_x_m) {
  const double travel_m = track_exit_m(scene) - start_x_m + scene.train.length_m();
  return travel_m / scene.speed_mps + free_vibration_s(scene.analysis) + scene.analysis.extra_time_s;
}

namespace {

// An operator given by the caller (a cache) must be the one this scene
// needs: built for its structure, dt and HHT parameters, with the rail
// flexibility when wheels are in contact. Anything else would be read past
// its tables or silently integrate another scheme.
void check_operator(const StructureOperator& op, const Scene& scene, const HhtCoefficients& h) {
  const StructureModel& s = *scene.structure;
  if (op.model_dofs() != s.num_dofs())
    throw InputError("/structure", fmt::format("the structure operator has {} DOFs, the structure {}", op.model_dofs(),
                                               s.num_dofs()));
  const EffectiveMatrixFactors want = structure_factors(h);
  const EffectiveMatrixFactors& got = op.factors();
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); };
  if (!same(want.mass, got.mass) || !same(want.damping, got.damping) || !same(want.stiffness, got.stiffness))
    throw InputError("/analysis", fmt::format("the structure operator was built for another dt or HHT alpha "
                                              "(K_bar factors {:g}, {:g}, {:g}; this scene needs {:g}, {:g}, {:g})",
                                              got.mass, got.damping, got.stiffness, want.mass, want.damping,
                                              want.stiffness));
  if (!scene.train.is_moving_forces() &&
      op.rail_flexibility().rows() != static_cast<Eigen::Index>(s.rail_dofs().size()))
    throw InputError("/structure", "the structure operator was built without the rail flexibility a multibody "
                                   "train needs");
}

}  // namespace

std::pair<double, double> bridge_extent_m(const StructureModel& structure) {
  const StructureInfo& info = structure.info();
  const RailLine& rail = structure.rails().front();
  if (info.bridge_end_m > info.bridge_start_m) return {info.bridge_start_m, info.bridge_end_m};
  return {rail.start_m(), rail.end_m()};
}

double default_start_x_m(const Scene& scene) {
  const double rail_start = scene.structure->rails().front().start_m();
  const double bridge_start = bridge_extent_m(*scene.structure).first;
  const double whole_train_on_track = rail_start + scene.train.length_m() + 1.0;
  return std::max(rail_start, std::min(bridge_start, whole_train_on_track));
}

namespace {

double planned_duration_s(const Scene& scene, double start_x_m) {
  return scene.analysis.duration_s.value_or(scene.speed_mps > 0.0 ? default_duration_s(scene, start_x_m) : 0.0);
}

long step_count(double duration_s, double dt_s) { return static_cast<long>(std::ceil(duration_s / dt_s - 1e-9)); }

}  // namespace

long planned_steps(const Scene& scene) {
  const double duration_s = planned_duration_s(scene, scene.start_x_m.value_or(default_start_x_m(scene)));
  if (!(duration_s > 0.0) || !std::isfinite(duration_s) || !(scene.analysis.dt_s > 0.0)) return 0;
  return step_count(duration_s, scene.analysis.dt_s);
}

StructureOperatorOptions structure_operator_options(const Scene& scene) {
  StructureOperatorOptions options;
  options.structure_backend = scene.analysis.structure_backend;
  options.modal_modes = scene.analysis.modal_modes;
  options.modal_cutoff_hz = scene.analysis.modal_cutoff_hz;
  options.hybrid_bridge_modes = scene.analysis.hybrid_bridge_modes;
  options.rail_flexibility = !scene.train.is_moving_forces();
  options.modal_static_correction = scene.analysis.modal_static_correction;
  return options;
}

std::shared_ptr<const StructureOperator> make_structure_operator(const Scene& scene,
                                                                 std::shared_ptr<const ModalBasis> modal_basis,
                                                                 std::shared_ptr<const HybridBasis> hybrid_basis) {
  const HhtCoefficients h(scene.analysis.hht, scene.analysis.dt_s);
  StructureOperatorOptions options = structure_operator_options(scene);
  options.modal_basis = std::move(modal_basis);
  options.hybrid_basis = std::move(hybrid_basis);
  return make_structure_operator(scene.structure, structure_factors(h), options);
}

std::shared_ptr<const HybridBasis> make_hybrid_basis(const Scene& scene) {
  return make_hybrid_basis(scene.structure, structure_operator_options(scene));
}

RunEstimate estimate_run(const Scene& scene, double duration_s) {
  RunEstimate e;
  const AnalysisOptions& an = scene.analysis;
  e.steps = std::ceil(duration_s / an.dt_s);
  double wheels = 0.0, bodies = 0.0;
  for (const TrainVehicle& v : scene.train.vehicles) {
    wheels += static_cast<double>(v.model->wheels().size() * an.contact.rail_lines.size());
    bodies += static_cast<double>(v.model->body_dofs().size());
  }
  const double channels = 1.0 + 2.0 * static_cast<double>(scene.structure->outputs().size()) + wheels + bodies;
  e.history_bytes = (e.steps / std::max(1, an.history_stride) + 1.0) * channels * sizeof(double);
  e.work = e.steps * (static_cast<double>(scene.structure->num_dofs()) +
                      4.0 * static_cast<double>(scene.train.moving_forces.size()) + wheels);
  return e;
}

// What the constructor prepares once and every run() reads.
struct SimulationSetup {
  HhtCoefficients h;
  double start_x_m = 0.0;
  double duration_s = 0.0;
  TrainLayout layout;
  std::vector<VehicleOperator> vehicle_ops;  // factorized once, copied per run
  StaticState statics;
  double setup_s = 0.0;
  SectionForms section_forms;
  DeckTwistGauge twist;
  // On the modal structure: the section forms on its modes (null on the FE
  // structure, or when none are asked or possible: section_forms says why).
  std::shared_ptr<const ModalSectionForces> modal_sections;
};

Simulation::Simulation(Scene scene, std::shared_ptr<const StructureOperator> op)
    : scene_(std::move(scene)), op_(std::move(op)) {
  const auto t_start = Clock::now();
  const AnalysisOptions& an = scene_.analysis;
  const double x0 = scene_.start_x_m.value_or(default_start_x_m(scene_));
  const double duration = planned_duration_s(scene_, x0);
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw InputError("/analysis/duration_s", "the run has no duration: give speed_kmh > 0 or analysis.duration_s");
  if (!an.allow_large_run) {
    const RunEstimate e = estimate_run(scene_, duration);
    const RunLimits limits;
    const auto refuse = [&](const char* what, double value, double limit) {
      throw InputError("/analysis/dt_s",
                       fmt::format("the run would take {:.3g} {} (limit {:.3g}): {:.6g} s of simulated time at "
                                   "dt = {:.3g} s; check dt_s, duration_s and speed_kmh, or run it with "
                                   "--allow-large",
                                   value, what, limit, duration, an.dt_s));
    };
    if (!(e.steps <= limits.max_steps)) refuse("steps", e.steps, limits.max_steps);
    if (!(e.history_bytes <= limits.max_history_bytes))
      refuse("bytes of histories", e.history_bytes, limits.max_history_bytes);
    if (!(e.work <= limits.max_work)) refuse("DOF-steps", e.work, limits.max_work);
  }
  const auto& rails = an.contact.rail_lines;
  for (std::size_t i = 0; i < rails.size(); ++i)
    if (rails[i] < 0 || rails[i] >= static_cast<int>(scene_.structure->rails().size()))
      throw InputError(fmt::format("/analysis/contact/rail_lines/{}", i),
                       fmt::format("rail line {} does not exist: the structure has {}", rails[i],
                                   scene_.structure->rails().size()));
  if (rails.size() > 1 && !scene_.train.is_moving_forces() && make_contact_law(an.contact)->is_constraint())
    throw InputError("/analysis/contact/rail_lines",
                     "a rigid wheelset on several rails has an indeterminate load split where it runs "
                     "on the rigid path: use a compliant law (hertz or linear-hertz)");
  auto setup = std::make_unique<SimulationSetup>(
      SimulationSetup{HhtCoefficients(an.hht, an.dt_s), x0, duration, TrainLayout(scene_.train, an.contact), {}, {}, 0.0, {},
                      make_deck_twist_gauge(*scene_.structure, an.contact.rail_lines), nullptr});
  check_rigid_contact_alpha(setup->layout, an.hht.alpha);
  if (an.solver == SolverPath::kReference && an.structure_backend != StructureBackend::kFiniteElements)
    throw InputError("/analysis/solver", "the reference path assembles the finite-element structure: use "
                                         "\"structure\": \"fe\" with \"solver\": \"reference\"");
  if (!op_ && an.solver == SolverPath::kCondensed) op_ = make_structure_operator(scene_);
  if (op_ && an.solver == SolverPath::kCondensed) check_operator(*op_, scene_, setup->h);
  setup->vehicle_ops = make_vehicle_operators(setup->layout, setup->h);
  // The static state of the backend the run integrates (the same modes).
  StructureOperatorOptions fe_statics;
  fe_statics.rail_flexibility = false;
  const auto statics_op = op_ && an.solver == SolverPath::kCondensed
                              ? op_->static_operator(*scene_.structure)
                              : make_structure_operator(scene_.structure, {0.0, 0.0, 1.0}, fe_statics);
  setup->statics = static_equilibrium(scene_, setup->layout, x0, *statics_op);
  // Section forces of a beam deck: forms of the FE DOFs, or on the modal
  // structure the same forms on its modes by mode acceleration (their
  // static part from a factor of K: the modal static operator would miss
  // the static share of the modes above the cut-off).
  setup->section_forms = make_section_forms(*scene_.structure);
  if (op_ && an.solver == SolverPath::kCondensed && setup->section_forms.available()) {
    if (const StructureCoordinates coords = op_->coordinates(*scene_.structure); coords.hybrid())
      setup->section_forms = forms_in_coordinates(std::move(setup->section_forms), coords);
  }
  const auto* modal = an.solver == SolverPath::kCondensed ? dynamic_cast<const ModalOperator*>(op_.get()) : nullptr;
  if (modal && setup->section_forms.available()) {
    if (scene_.fidelity.asks_section_forces())
      setup->modal_sections = std::make_shared<const ModalSectionForces>(modal->basis(), rails);
    else
      setup->section_forms.unavailable = kSectionForcesNotAsked;
  }
  for (std::size_t c = 0; c < setup->layout.contacts.size(); ++c)
    setup->layout.contacts[c].law =
        setup->layout.contacts[c].law->at_static_load(setup->statics.P[static_cast<Eigen::Index>(c)]);
  setup->setup_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  setup_ = std::move(setup);
}

Simulation::~Simulation() = default;

Result Simulation::run() const {
  const auto t_start = Clock::now();
  Result result;
  RunSummary& sum = result.summary;
  const Scene& sc = scene_;
  const AnalysisOptions& an = sc.analysis;
  const SimulationSetup& setup = *setup_;
  const HhtCoefficients& h = setup.h;
  const TrainLayout& layout = setup.layout;
  const StaticState& statics = setup.statics;
  const double x0 = setup.start_x_m;

  StepSolverOptions so;
  so.alpha = h.alpha;
  so.max_iterations = an.max_newton_iterations;
  so.tolerance = an.newton_tolerance;
  so.force_scale_N = std::max(1.0, statics.P.norm());
  std::unique_ptr<StepSolver> solver;
  const StructureCoordinates coords = op_ ? op_->coordinates(*sc.structure) : StructureCoordinates(*sc.structure);
  if (an.solver == SolverPath::kReference) {
    solver = make_reference_step_solver(*sc.structure, structure_factors(h), layout, h, so);
    sum.fidelity.structure_backend = "umfpack-bordered";
  } else {
    solver = make_condensed_step_solver(op_, coords, layout, setup.vehicle_ops, so);
    sum.fidelity.structure_backend = op_->backend_name();
  }

  // Fidelity record.
  const bool mf = sc.train.is_moving_forces();
  sum.fidelity.model = load_model_name(mf ? LoadModel::kMovingForces : LoadModel::kInteraction);
  sum.fidelity.contact_law = mf ? "none" : std::string(make_contact_law(an.contact)->name());
  sum.fidelity.unilateral = !mf && !layout.contacts.empty() && layout.contacts.front().law->unilateral();
  sum.fidelity.solver_path = an.solver == SolverPath::kReference ? "reference" : "condensed";
  sum.fidelity.structure_dofs = sc.structure->num_dofs();
  if (an.structure_backend == StructureBackend::kHybrid && op_) {
    // The bridge's modes (free-interface by default: BridgeModes) and their cut-off.
    const auto* hybrid = dynamic_cast<const HybridOperator*>(op_.get());
    sum.fidelity.modes = hybrid ? hybrid->basis().num_modes() : 0;
    sum.fidelity.modal_cutoff_hz =
        hybrid ? hybrid->basis().cutoff_hz() : std::numeric_limits<double>::quiet_NaN();
  }
  if (an.structure_backend == StructureBackend::kModal && op_) {
    // The modal operator's unknowns are the modes; their cut-off is the
    // scene's (null when the scene gives a mode count instead).
    sum.fidelity.modes = op_->num_dofs();
    sum.fidelity.modal_cutoff_hz = an.modal_modes > 0 ? std::numeric_limits<double>::quiet_NaN()
                                   : an.modal_cutoff_hz > 0.0 ? an.modal_cutoff_hz
                                                              : kDefaultModalCutoffHz;
    // As the step applies it: not on the rigid path (condensed_step_solver).
    sum.fidelity.static_correction = op_->rail_residual_flexibility() != nullptr && !layout.contacts.empty() &&
                                     !layout.contacts.front().law->is_constraint();
    // The backend's name says what the operator holds; the record says what
    // the run applied (rigid contact, moving forces: no static correction).
    const std::string held = ", static correction";
    if (const auto at = sum.fidelity.structure_backend.find(held);
        !sum.fidelity.static_correction && at != std::string::npos)
      sum.fidelity.structure_backend.replace(at, held.size(), ", no static correction");
  }
  sum.fidelity.vehicle_dofs = layout.num_vehicle_dofs;
  sum.fidelity.contacts = static_cast<int>(layout.contacts.size());
  sum.fidelity.hht_alpha = h.alpha;
  sum.fidelity.hht_beta = h.beta;
  sum.fidelity.hht_gamma = h.gamma;
  sum.dt_s = an.dt_s;
  sum.static_wheel_load_N.assign(statics.P.data(), statics.P.data() + statics.P.size());

  RunState state(sc, layout, statics, x0, coords,
                 setup.modal_sections ? setup.modal_sections->forms() : setup.section_forms, setup.twist,
                 setup.modal_sections.get());
  sum.setup_s = setup.setup_s + std::chrono::duration<double>(Clock::now() - t_start).count();
  const long steps = step_count(setup.duration_s, an.dt_s);
  state.record(0, 0.0, result.histories, /*store=*/true);
  for (long n = 0; n < steps; ++n) {
    const double t_new = (n + 1) * an.dt_s;
    int iterations = 0;
    const Status st = state.step(h, t_new, *solver, iterations);
    sum.newton_iterations += iterations;
    sum.max_newton_iterations_in_step = std::max(sum.max_newton_iterations_in_step, iterations);
    if (!st.ok()) {
      result.status = {st.code(), fmt::format("step {} (t = {:.6f} s, first axle at x = {:.3f} m): {}",
                                              n + 1, t_new, x0 + sc.speed_mps * t_new, st.message())};
      break;
    }
    sum.steps = n + 1;
    const bool store = ((n + 1) % std::max(1, an.history_stride) == 0) || n + 1 == steps;
    state.record(n + 1, t_new, result.histories, store);
  }
  state.summarize(sum);
  sum.wall_s = setup.setup_s + std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace railvsi

#pragma once
// One run of the direct method (Neves et al. (2014), Eng. Struct. 69, 83-89;
// README "The method").
// The Simulation holds only const things; run() creates the per-run state.
#include <memory>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "solver/hybrid_basis.hpp"
#include "solver/modal_basis.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

// Build the structure operator a scene needs (K_bar factor and rail
// flexibility for its dt and HHT parameters). Shareable between runs with
// the same key. Throws InputError if the structure cannot be factorized.
// A modal or hybrid basis computed before (same structure, same modes) is
// reused instead of computed again (operators for several dt).
std::shared_ptr<const StructureOperator> make_structure_operator(const Scene& scene,
                                                                 std::shared_ptr<const ModalBasis> modal_basis = nullptr,
                                                                 std::shared_ptr<const HybridBasis> hybrid_basis = nullptr);

// The hybrid structure's reduction a scene asks for (its bridge modes: a
// count or a cut-off), for operators of several dt to share. Throws
// InputError as HybridBasis does.
std::shared_ptr<const HybridBasis> make_hybrid_basis(const Scene& scene);

// Time simulated by default: until the last axle has left the modelled track
// (every rail end, and the evaluation margin past the bridge), then the free
// vibration (free_vibration_s below), plus the extra time asked for.
double default_duration_s(const Scene& scene, double start_x_m);
// Free vibration after the last axle has left, s: analysis.free_vibration_s
// when given, else max(min_s, min(periods / f0, 10 s)) (min_s while f0 is
// unknown).
inline constexpr double kMaxDefaultFreeVibrationS = 10.0;
double free_vibration_s(const AnalysisOptions& analysis);
// x the last axle must pass to have left the modelled track: the furthest
// rail end, and at least the evaluation margin past the bridge.
double track_exit_m(const Scene& scene);
// Time steps a run of the scene takes (its duration over dt, as run()
// counts them); 0 when the scene has no duration. Cost estimates use it.
long planned_steps(const Scene& scene);
// What a run will cost, estimated before anything is allocated.
struct RunEstimate {
  double steps = 0.0;
  double history_bytes = 0.0;  // the stored histories
  double work = 0.0;           // steps x (structure DOFs + axle loads): the time loop's operations, roughly
};
struct RunLimits {
  double max_steps = 2.0e6;
  double max_history_bytes = 2.0 * (1ull << 30);
  double max_work = 2.0e11;
};
RunEstimate estimate_run(const Scene& scene, double duration_s);

class Simulation {
 public:
  // Accepts the scene: static equilibrium of train and structure, the
  // structure operator when `op` is null (shareable between runs with the
  // same structure, dt and HHT parameters). Throws InputError when the
  // scene cannot be run (a mechanism, a train its wheels cannot carry, no
  // duration, a run beyond RunLimits unless analysis.allow_large_run, an
  // operator `op` built for another dt, HHT alpha or without the rail
  // flexibility the train needs). The scene is copied: it holds only shared
  // immutable models.
  explicit Simulation(Scene scene, std::shared_ptr<const StructureOperator> op = nullptr);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // The time loop. Never throws for numerical trouble: the status of the
  // Result tells. May be called several times, from several threads.
  Result run() const;

 private:
  Scene scene_;
  std::shared_ptr<const StructureOperator> op_;
  std::unique_ptr<const struct SimulationSetup> setup_;
};

}  // namespace railvsi

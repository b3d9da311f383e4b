#include "planning/accuracy_price.hpp"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <thread>

#include "planning/run_planning_warnings.hpp"
#include "solver/modal_basis.hpp"
#include "planning/effects_planner.hpp"
#include "solver/hybrid_basis.hpp"
#include "core/input_error.hpp"
#include "envelopes/code_filter.hpp"
#include "envelopes/job_envelopes.hpp"
#include "planning/cost_model.hpp"
#include "planning/fidelity_ladder.hpp"
#include "planning/rung_runner.hpp"
#include "price/dt_self_check.hpp"
#include "simulation/simulation.hpp"

namespace railvsi {
namespace {

using Clock = std::chrono::steady_clock;

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Thread CPU and wall time of f().
template <class F>
auto measured(F&& f, double& cpu_s, double& wall_s) {
  const double cpu0 = thread_cpu_s();
  const auto wall0 = Clock::now();
  struct Stop {
    double cpu0;
    Clock::time_point wall0;
    double& cpu_s;
    double& wall_s;
    ~Stop() {
      cpu_s = thread_cpu_s() - cpu0;
      wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
    }
  } stop{cpu0, wall0, cpu_s, wall_s};
  return f();
}

// Something built once and shared by the runs (an operator per dt, the
// modal basis), with what building it cost.
template <class T>
struct Built {
  std::shared_ptr<const T> value;
  double cpu_s = 0.0, wall_s = 0.0;
};

// Built once per key, by the first thread that asks; the others wait for
// it (an exception of the build reaches every caller).
template <class Key, class T>
class OnceCache {
 public:
  Built<T> get(const Key& key, const std::function<std::shared_ptr<const T>()>& build) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto it = entries_.find(key);
    if (it != entries_.end()) {
      const std::shared_future<Built<T>> future = it->second;
      lock.unlock();
      return future.get();
    }
    std::promise<Built<T>> promise;
    const std::shared_future<Built<T>> future = promise.get_future().share();
    entries_.emplace(key, future);
    lock.unlock();
    try {
      Built<T> b;
      b.value = measured(build, b.cpu_s, b.wall_s);
      promise.set_value(b);
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
    return future.get();
  }

 private:
  std::mutex mutex_;
  std::map<Key, std::shared_future<Built<T>>> entries_;
};

struct Task {
  std::size_t rung = 0;
  double dt_s = 0.0;
};

}  // namespace

PriceReport price_scene(const Scene& scene, const PriceOptions& options) {
  const auto wall0 = Clock::now();
  PriceReport report;
  report.threads = std::max(1, options.threads);
  report.cutoff_hz = code_cutoff_hz(options.f0_hz, options.f3_hz);
  const std::vector<LadderRung>& ladder = fidelity_ladder();

  std::vector<std::size_t> rungs;
  for (std::size_t r = 0; r < ladder.size(); ++r)
    if (rung_applies(ladder[r], scene)) rungs.push_back(r);
  // The policy's dt of the most complete rung: one dt ladder for all rungs.
  const Scene most_complete = rung_scene(ladder[rungs.back()], scene, scene.analysis.dt_s);
  const TimeStepChoice policy =
      choose_time_step(*most_complete.structure, most_complete.train, most_complete.speed_mps,
                       most_complete.analysis.contact, options.f0_hz, options.f3_hz, options.policy,
                       most_complete.irregularity.get());
  report.policy_dt_s = policy.dt_s;
  report.policy_reason = policy.reason;

  std::vector<Task> tasks;
  const double base_dt_s = options.base_dt_s > 0.0 ? options.base_dt_s : policy.dt_s;
  for (std::size_t r : rungs)
    for (double f : options.dt_factors) tasks.push_back({r, base_dt_s * f});
  std::vector<PriceRow> rows(tasks.size());

  OnceCache<double, StructureOperator> operators, modal_operators, hybrid_operators;
  OnceCache<int, ModalBasis> bases;
  OnceCache<int, HybridBasis> hybrid_bases;
  const auto operator_of = [&](double dt_s) {
    return operators.get(dt_s, [&] {
      // Built for the scene's own train: with the rail flexibility when it
      // has wheels, which the moving-force rungs leave unused.
      Scene s = scene;
      s.analysis.dt_s = dt_s;
      return make_structure_operator(s);
    });
  };
  const auto basis_of = [&] {
    return bases.get(0, [&] {
      ModalBasisOptions o;
      o.max_frequency_hz = options.modal_cutoff_factor * report.cutoff_hz;
      return std::make_shared<const ModalBasis>(scene.structure, o);
    });
  };

  // The hybrid rungs: the bridge's modes up to the planner's cut-off for
  // the hybrid structure, computed once; an operator per dt.
  const auto hybrid_basis_of = [&] {
    return hybrid_bases.get(0, [&] {
      HybridBasisOptions o;
      o.max_frequency_hz = kHybridCutoffFactor * report.cutoff_hz;
      return std::make_shared<const HybridBasis>(scene.structure, o);
    });
  };
  const auto hybrid_operator_of = [&](const Scene& s, const std::shared_ptr<const HybridBasis>& basis) {
    return hybrid_operators.get(s.analysis.dt_s, [&] { return make_structure_operator(s, nullptr, basis); });
  };

  // The modal interaction rungs: the same modes, an operator per dt.
  const auto modal_operator_of = [&](const Scene& s, const std::shared_ptr<const ModalBasis>& basis) {
    return modal_operators.get(s.analysis.dt_s, [&] { return make_structure_operator(s, basis); });
  };

  const auto run_task = [&](std::size_t i) {
    const Task& task = tasks[i];
    const LadderRung& rung = ladder[task.rung];
    PriceRow& row = rows[i];
    row.model = rung.model_name();
    row.structure = rung.structure_name();
    row.contact_law = rung.contact_law;
    row.rung = static_cast<int>(task.rung);
    row.dt_s = task.dt_s;
    try {
      Scene s = rung_scene(rung, scene, task.dt_s);
      // What the run shares with others is built (or waited for) first,
      // outside the run's own timing, and charged to every row using it.
      Built<StructureOperator> op;
      Built<ModalBasis> basis;
      if (rung.structure == StructureBackend::kFiniteElements) op = operator_of(task.dt_s);
      if (rung.structure == StructureBackend::kModal) basis = basis_of();
      if (rung.structure == StructureBackend::kModal && rung.model == LoadModel::kInteraction) {
        s.analysis.modal_cutoff_hz = basis.value->max_frequency_hz();
        op = modal_operator_of(s, basis.value);
      }
      Built<HybridBasis> hybrid;
      if (rung.structure == StructureBackend::kHybrid) {
        hybrid = hybrid_basis_of();
        s.analysis.modal_cutoff_hz = hybrid.value->cutoff_hz();
        op = hybrid_operator_of(s, hybrid.value);
        row.modes = hybrid.value->num_modes();
      }
      if (basis.value) row.modes = basis.value->num_modes();
      row.setup_cpu_s = op.cpu_s + basis.cpu_s + hybrid.cpu_s;
      // The cost model has no fit for interaction on the modes: no prediction.
      if (!(rung.structure == StructureBackend::kModal && rung.model == LoadModel::kInteraction))
        row.cpu_predicted_s = predict_cost(cost_inputs(s, rung.structure, row.modes.value_or(0))).total_cpu_s();
      // The run as a worker runs a job (run_at_rung), on what was built above.
      const ScenePlan plan = ladder_plan(rung, basis.value ? basis.value->max_frequency_hz() : s.analysis.modal_cutoff_hz);
      RungModels models;
      models.fe_operator = [&](const Scene&, const std::shared_ptr<const HybridBasis>&) { return op.value; };
      models.modal_basis = [&](double) { return basis.value; };
      double cpu_s = 0.0, wall_s = 0.0;
      const Result result = measured([&] { return run_at_rung(s, plan, models); }, cpu_s, wall_s);
      row.cpu_s = cpu_s + row.setup_cpu_s;
      row.wall_s = wall_s + op.wall_s + basis.wall_s + hybrid.wall_s;
      row.steps = result.summary.steps;
      // The run's health warnings, and the planning layer's, as vsi
      // simulate adds them.
      std::vector<RunWarning> warnings = result.summary.warnings;
      for (RunWarning& w : run_planning_warnings(s, result.summary, report.cutoff_hz)) warnings.push_back(std::move(w));
      for (const RunWarning& w : warnings)
        if (std::find(row.warnings.begin(), row.warnings.end(), w.code) == row.warnings.end())
          row.warnings.push_back(w.code);
      const JobEnvelopes e = compute_envelopes(result, s.analysis.dt_s, s.analysis.history_stride, report.cutoff_hz);
      row.status = e.status;
      row.message = e.message.empty() ? result.status.message() : e.message;
      row.values = key_quantity_values(e);
    } catch (const InputError& e) {
      row.status = "refused";
      row.message = e.describe();
    } catch (const std::exception& e) {
      row.status = "failed";
      row.message = e.what();
    }
  };

  // The finest steps first: the longest runs start early and the pool
  // ends evenly.
  std::vector<std::size_t> order(tasks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tasks[a].dt_s < tasks[b].dt_s; });
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t k; (k = next.fetch_add(1)) < order.size();) run_task(order[k]);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < report.threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  if (std::all_of(rows.begin(), rows.end(), [](const PriceRow& r) { return r.status == "refused"; }))
    throw InputError("", rows.empty() ? "no rung applies to the scene" : rows.front().message);
  report.rows = std::move(rows);
  report.reference = price_errors(report.rows);
  report.pareto = pareto_fronts(report.rows);
  report.cheapest_1pct = cheapest_within(report.rows, 0.01);
  report.cheapest_5pct = cheapest_within(report.rows, 0.05);
  report.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  return report;
}

}  // namespace railvsi

#include "cli/inspect_report.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "analysis/frequency_units_check.hpp"
#include "solver/modal_analysis.hpp"
#include "analysis/mode_classification.hpp"
#include "analysis/span_supports.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi::cli {
namespace {

using nlohmann::ordered_json;

ordered_json finite_or_null(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

}  // namespace

ordered_json resonance_report(const Train& train, double f0_hz, double min_kmh, double max_kmh) {
  if (!(train.coach_length_m > 0.0) || !(f0_hz > 0.0)) return nullptr;
  ordered_json speeds = ordered_json::array();
  for (int i = 1; i <= 4; ++i) {
    const double v_kmh = f0_hz * train.coach_length_m / i * 3.6;
    if (v_kmh >= min_kmh && v_kmh <= max_kmh) speeds.push_back({{"i", i}, {"speed_kmh", v_kmh}});
  }
  return {{"train", train.name}, {"coach_length_m", train.coach_length_m}, {"f0_hz", f0_hz}, {"speeds", speeds}};
}

ordered_json structure_report(const StructureModel& s) {
  const StructureInfo& info = s.info();
  ordered_json rails = ordered_json::array();
  for (const RailLine& r : s.rails())
    rails.push_back({{"name", r.name}, {"nodes", r.x_m.size()}, {"start_m", r.start_m()}, {"end_m", r.end_m()}});
  ordered_json outputs = ordered_json::array();
  for (const OutputPoint& p : s.outputs()) outputs.push_back({{"name", p.name}, {"x_m", p.x_m}});
  return {{"source", info.source},
          {"dofs", s.num_dofs()},
          {"deck_dofs", info.deck_dofs},
          {"track_dofs", info.track_dofs},
          {"rail_lines", rails},
          {"bridge_start_m", info.bridge_start_m},
          {"bridge_end_m", info.bridge_end_m},
          {"supports_m", info.support_x_m},
          {"damping_ratio", info.damping_ratio ? finite_or_null(*info.damping_ratio) : ordered_json(nullptr)},
          {"damping_source", info.damping_source},
          {"rayleigh_f1_estimate_hz", info.first_frequency_hz > 0.0 ? ordered_json(info.first_frequency_hz)
                                                                     : ordered_json(nullptr)},
          {"output_points", outputs},
          {"import", info.source == "import" ? ordered_json{{"matched", info.import_notes},
                                                             {"warnings", info.import_warnings}}
                                             : ordered_json(nullptr)}};
}

ordered_json modal_report(const StructureModel& s, int modes) {
  ModalOptions options;
  options.modes = modes;
  const ModalResult r = modal_analysis(s, options);
  ordered_json out;
  out["status"] = std::string(r.status.name());
  if (!r.status.ok()) {
    out["message"] = r.status.message();
    out["modes"] = ordered_json::array();
    return out;
  }
  out["solver"] = r.solver == ModeSolver::kSubspace
                      ? fmt::format("subspace iteration, {} iterations", r.iterations)
                      : std::string("Lanczos");
  out["modes"] = ordered_json::array();
  if (!r.frequencies_hz.empty() && s.info().source == "import")
    if (const auto warning = frequency_units_warning(r.frequencies_hz.front())) out["units_warning"] = *warning;
  const SpanSupports supports = span_supports(s, r);
  if (supports.from_modes)
    out["supports_from_modes"] = {
        {"supports_m", supports.x_m},
        {"modes_used", supports.modes_used},
        {"largest_rest", supports.largest_rest},
        {"note", fmt::format("the map gives no supports_x_m: {} interior support(s) read from the {} lowest deck "
                             "modes (at most {:.1f} % of a mode's largest displacement there); give supports_x_m to "
                             "state them",
                             supports.x_m.size() - 2, supports.modes_used, 100.0 * supports.largest_rest)}};
  for (std::size_t k = 0; k < r.frequencies_hz.size(); ++k) {
    const ModeType type = classify_mode(s, r.shapes.col(static_cast<Eigen::Index>(k)), supports.x_m,
                                        supports.from_modes ? kReadSupportBand : 0.0);
    out["modes"].push_back({{"n", k + 1},
                            {"frequency_hz", r.frequencies_hz[k]},
                            {"type", type.description},
                            {"deck_energy_fraction", type.deck_energy_fraction},
                            {"half_waves_per_span", type.half_waves}});
  }
  return out;
}

ordered_json train_report(const Train& train) {
  ordered_json axles = ordered_json::array();
  double total_N = 0.0;
  for (const MovingForce& f : train.moving_forces) {
    axles.push_back({{"offset_m", f.offset_m}, {"static_load_N", f.load_N}});
    total_N += f.load_N;
  }
  int vehicle_dofs = 0;
  double mass_kg = 0.0;
  for (const TrainVehicle& v : train.vehicles) {
    const Vector loads = static_wheel_loads_on_rigid_track(*v.model);
    const auto& wheels = v.model->wheels();
    for (std::size_t w = 0; w < wheels.size(); ++w) {
      axles.push_back({{"offset_m", v.offset_m + wheels[w].offset_m},
                       {"static_load_N", loads[static_cast<Eigen::Index>(w)]},
                       {"vehicle", v.model->name()}});
      total_N += loads[static_cast<Eigen::Index>(w)];
    }
    vehicle_dofs += v.model->num_dofs();
    mass_kg += v.model->total_mass_kg();
  }
  ordered_json out = {{"name", train.name},
                      {"model", train.is_moving_forces() ? "moving_forces" : "multibody"},
                      {"axles", train.num_axles()},
                      {"length_m", train.length_m()},
                      {"total_static_load_N", total_N}};
  if (!train.is_moving_forces()) {
    out["vehicles"] = train.vehicles.size();
    out["vehicle_dofs"] = vehicle_dofs;
    out["total_mass_kg"] = mass_kg;
  }
  out["axle_list"] = axles;
  return out;
}

ordered_json irregularity_report(const Irregularity& irregularity) {
  const auto& x = irregularity.x_m();
  const auto& r = irregularity.r_m();
  double integral_r = 0.0, integral_r2 = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double h = x[i + 1] - x[i];
    integral_r += 0.5 * h * (r[i] + r[i + 1]);
    integral_r2 += 0.5 * h * (r[i] * r[i] + r[i + 1] * r[i + 1]);
  }
  const double length = x.back() - x.front();
  const auto [min, max] = std::minmax_element(r.begin(), r.end());
  return {{"source", irregularity.source()},
          {"samples", x.size()},
          {"x_start_m", x.front()},
          {"x_end_m", x.back()},
          {"min_m", *min},
          {"max_m", *max},
          {"mean_m", finite_or_null(integral_r / length)},
          {"rms_m", finite_or_null(std::sqrt(integral_r2 / length))}};
}

}  // namespace railvsi::cli

#include "planning/time_step_policy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "envelopes/code_filter.hpp"
#include "planning/track_feature.hpp"
#include "simulation/static_equilibrium.hpp"

namespace railvsi {
namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("choose_time_step: ") + what);
}

bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

double max_omega_dt(const HhtParameters& hht, double max_period_error) {
  // The period error grows monotonically with Omega = omega dt (as Omega^2
  // for small Omega): bisect on [0, 1] (Omega = 1 is 6.3 steps per period).
  double lo = 0.0, hi = 1.0;
  if (hht_period_error(hht, hi) <= max_period_error) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (hht_period_error(hht, mid) <= max_period_error ? lo : hi) = mid;
  }
  return lo;
}

double shortest_rail_element_m(const StructureModel& structure) {
  double h = std::numeric_limits<double>::infinity();
  for (const RailLine& rail : structure.rails())
    for (std::size_t i = 0; i + 1 < rail.x_m.size(); ++i) h = std::min(h, rail.x_m[i + 1] - rail.x_m[i]);
  return h;
}

double highest_contact_frequency_hz(const Train& train, const ContactOptions& contact) {
  if (train.is_moving_forces() || make_contact_law(contact)->is_constraint()) return 0.0;
  double f_max = 0.0;
  std::set<const VehicleModel*> seen;  // one vehicle type is shared by many cars
  for (const TrainVehicle& tv : train.vehicles) {
    if (!seen.insert(tv.model.get()).second) continue;
    const VehicleModel& v = *tv.model;
    const Vector loads = static_wheel_loads_on_rigid_track(v);
    for (std::size_t w = 0; w < v.wheels().size(); ++w) {
      const Wheel& wheel = v.wheels()[w];
      const double Q = std::max(0.0, loads[static_cast<Eigen::Index>(w)]);
      // The law's tangent stiffness at the static load.
      const auto law = make_contact_law(contact, {wheel.radius_m, 1})->at_static_load(Q);
      const double k = law->stiffness(law->compression(Q));
      const double m = v.M()(wheel.dof, wheel.dof);
      if (m > 0.0) f_max = std::max(f_max, std::sqrt(k / m) / (2.0 * std::numbers::pi));
    }
  }
  return f_max;
}

TimeStepChoice choose_time_step(const StructureModel& structure, const Train& train, double speed_mps,
                                const ContactOptions& contact, double f0_hz, double f3_hz,
                                const TimeStepPolicy& policy, const Irregularity* profile) {
  require(finite_non_negative(speed_mps), "speed_mps must be finite and >= 0");
  require(finite_non_negative(f0_hz) && finite_non_negative(f3_hz), "f0_hz and f3_hz must be finite and >= 0");
  require(policy.dt_max_s > 0.0 && policy.max_period_error > 0.0 && policy.max_travel_fraction_of_element > 0.0 &&
              policy.contact_steps_per_period > 0.0 && policy.track_steps_per_feature > 0.0 &&
              policy.impact_steps_per_feature > 0.0 && policy.rigid_steps_per_element > 0.0,
          "policy values must be > 0");

  TimeStepChoice c;
  const double f_cut = code_cutoff_hz(f0_hz, f3_hz);
  const double omega_dt = max_omega_dt(policy.hht, policy.max_period_error);
  c.bounds.push_back({"code frequency", omega_dt / (2.0 * std::numbers::pi * f_cut),
                      fmt::format("f_cut = max(30, 1.5 f0 = {:.1f}, f3 = {:.1f}) = {:.1f} Hz with HHT period error "
                                  "<= {:g} % (alpha = {:g}: {:.1f} steps/period)",
                                  1.5 * f0_hz, f3_hz, f_cut, 100.0 * policy.max_period_error, policy.hht.alpha,
                                  2.0 * std::numbers::pi / omega_dt)});
  const double h = shortest_rail_element_m(structure);
  if (speed_mps > 0.0 && std::isfinite(h))
    c.bounds.push_back({"wheel travel", policy.max_travel_fraction_of_element * h / speed_mps,
                        fmt::format("wheel travel {:g} x {:.3f} m element at {:.1f} m/s",
                                    policy.max_travel_fraction_of_element, h, speed_mps)});
  if (speed_mps > 0.0 && std::isfinite(h) && contact.law == "rigid" && !train.is_moving_forces())
    c.bounds.push_back({"rigid contact", h / (policy.rigid_steps_per_element * speed_mps),
                        fmt::format("rigid contact: a wheel crosses each {:.3f} m rail element in {:g} steps at "
                                    "{:.1f} m/s (the rail's curvature jumps at its nodes)",
                                    h, policy.rigid_steps_per_element, speed_mps)});
  const double f_H = highest_contact_frequency_hz(train, contact);
  if (f_H > 0.0)
    c.bounds.push_back({"contact frequency", 1.0 / (policy.contact_steps_per_period * f_H),
                        fmt::format("Hertz contact f_H = {:.1f} Hz at {:g} steps/period", f_H,
                                    policy.contact_steps_per_period)});

  if (profile && !train.is_moving_forces() && speed_mps > 0.0) {
    const TrackFeature feature = shortest_track_feature(*profile);
    if (feature.wavelength_m > 0.0) {
      const double demand_mps2 = speed_mps * speed_mps * feature.max_curvature_per_m;
      const bool impact = demand_mps2 > policy.impact_acceleration_mps2;
      const double steps = impact ? policy.impact_steps_per_feature : policy.track_steps_per_feature;
      c.bounds.push_back({"track profile", feature.wavelength_m / (steps * speed_mps),
                          fmt::format("track profile: {} (v^2 r'' = {:.3g} m/s^2{}) crossed in {:g} steps at "
                                      "{:.1f} m/s",
                                      feature.describe(), demand_mps2, impact ? ": the wheel lifts and lands" : "",
                                      steps, speed_mps)});
    }
  }

  const auto binding = std::min_element(c.bounds.begin(), c.bounds.end(),
                                        [](const TimeStepBound& a, const TimeStepBound& b) { return a.dt_s < b.dt_s; });
  c.required_dt_s = binding->dt_s;
  c.binding = binding->name;
  // Largest rung not above the requirement; a requirement that equals a
  // rung up to round-off takes that rung.
  while (std::ldexp(policy.dt_max_s, -c.ladder_k) > c.required_dt_s * (1.0 + 1e-12) &&
         std::ldexp(policy.dt_max_s, -c.ladder_k - 1) >= policy.dt_min_s * (1.0 - 1e-12) && c.ladder_k < 60)
    ++c.ladder_k;
  c.dt_s = std::ldexp(policy.dt_max_s, -c.ladder_k);

  for (const TimeStepBound& b : c.bounds) c.reason += fmt::format("{} needs {:.2e} s; ", b.detail, b.dt_s);
  c.reason += fmt::format("binding: {}; ladder {:.1e} s / 2^{} = {:.3e} s", c.binding, policy.dt_max_s, c.ladder_k,
                          c.dt_s);
  if (c.dt_s > c.required_dt_s * (1.0 + 1e-12))
    c.reason += fmt::format(" (the ladder's floor: {:.3g} x the requirement, the run warns)", c.dt_s / c.required_dt_s);
  return c;
}

}  // namespace railvsi

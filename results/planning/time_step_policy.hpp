#pragma once
// The time step of a job whose study does not fix dt_s (the fidelity
// ladder): the largest step on the ladder dt_max / 2^k that meets every
// accuracy bound, so that jobs whose requirements fall in the same ladder
// interval share one structure factorization.
//
// The planner is the scheduler's; this rule lives beside the code filter
// because both start from the code frequency f_cut, and it depends on the
// models only (it builds and tests without the study service).
//
// Bounds (each a largest admissible dt):
//  1. code frequency: the HHT period elongation at
//     f_cut = max(30 Hz, 1.5 f0, f3), the highest frequency the deck
//     acceleration envelope keeps, stays <= max_period_error (0.25 %),
//     computed from the phase of the amplification matrix's principal
//     roots for the scene's alpha (hht_period_error). For alpha = -0.05 that
//     is 38.7 steps per period of f_cut. Steps per period alone did not
//     keep the promise: at 20 steps the period error is 0.93 %, and a mode
//     near f_cut excited at resonance (the third bending mode of a span,
//     f3 = 9 f0) then carried it into the filtered acceleration (up to 2 %
//     reported on an HSLM sweep; 1.18 % measured in time_step_policy_test
//     at 1 ms, 0.27 % at the 0.5 ms this bound gives). The bound on the
//     filtered deck acceleration is measured on that case, not derived. Lower modes
//     get more steps and smaller errors (as dt^2).
//  2. wheel travel: a wheel moves at most max_travel_fraction_of_element of
//     the shortest rail element per step. Loads enter through the Hermite
//     row of the element under each wheel at each step; 0.25 gives every
//     element (every sleeper bay of a track model) four load positions, so
//     the element- and sleeper-passing frequency v/h is sampled at half the
//     Nyquist frequency instead of being aliased.
//  3. contact frequency (multibody trains with a compliant contact law,
//     linear or nonlinear Hertz): contact_steps_per_period steps per period
//     of f_H = sqrt(k_H/m_w)/(2 pi), the wheel's mass m_w (its diagonal mass
//     entry) on the Hertz spring linearized at its static load,
//     k_H = 1.5 n (Q/n)^(1/3) / G. This is the wheel bouncing on a rigid
//     rail: an upper bound of the wheel-on-track (P2) frequencies that govern
//     unloading, which therefore get more steps than these 10 (10 steps at
//     f_H: period error 3.6 %, amplitude loss 0.74 % per cycle at
//     alpha = -0.05). The rail mass on the Hertz spring (P1, several hundred
//     Hz with a track) is not resolved: HHT's dissipation damps it. A rigid
//     contact has no frequency of its own: no bound.
//  4. track profile (multibody trains on an irregular track): a wheel
//     crosses the profile's shortest feature (a defect's length, the rise
//     of a step, the shortest wavelength of a spectrum as sampled) in at
//     least track_steps_per_feature steps. A short dip or a step makes the
//     wheel leave the rail and land again: the impact's time scale is the
//     feature's crossing time, not the structure's or the wheel's frequency.
//     Measured (one ICE3 coach over 2 x 15 m, Hertz, against dt = 15.6 us,
//     2026-11-27): a 30 mm x 1 m dip at 350 km/h needs 62.5 us (filtered
//     deck acceleration +0.07 %, contact-loss time +0.56 %; at 0.25 ms
//     +10.3 % and +6.0 %), a 30 mm x 0.5 m dip at 400 km/h 31.25 us (-0.24 %,
//     0.0 %; at 62.5 us -0.90 %, +1.05 %): about 150 steps per crossing of a
//     feature that lifts the wheel (v^2 r'' of 5,600 and 29,000 m/s^2).
//     Gentler features (a 5 mm x 2 m bump, v^2 r'' = 170 m/s^2 at 300 km/h;
//     the spectra) converged to 0.2 % at 0.25 ms: 40 steps.
//  5. rail elements under rigid contact: a rigid wheel follows the rail's
//     Hermite field, whose curvature jumps at every node (V^2 N'' u_s in the
//     wheel's acceleration), and a step sees such a jump only at its ends:
//     the result depends on where in a step each node crossing falls, by an
//     amount that falls steeply with the steps per element. Measured (ICE3,
//     3 x 25 m viaduct, 300 km/h, 0.6 m elements, smooth track; the train
//     started 0.6 m further each time, which only moves the crossings
//     within the steps by 0.2 of a step at 1 ms), the filtered deck
//     acceleration spread over 2.5 % at 7.2 steps per element (1 ms),
//     0.21 % at 14.4 (0.5 ms) and 0.093 % at 28.8 (0.25 ms); Hertz 0.005 %
//     at 1 ms. rigid_steps_per_element steps keep it about 0.4 %.
#include <string>
#include <vector>

#include "model/structure_model.hpp"
#include "model/train.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

struct TimeStepPolicy {
  // Top of the ladder. 2 ms is coarser than any deck needs (f_cut >= 30 Hz
  // at 20 steps per period needs 1.67 ms) and its halvings are round
  // numbers: 1, 0.5, 0.25, 0.125 ms.
  double dt_max_s = 2.0e-3;
  // Bottom of the ladder (dt_max / 2^7): a requirement below it (a step in
  // the profile, whose rise is one sample interval) takes this step, and the
  // run warns dt_above_policy with the factor and the feature
  // (time_step_warnings) instead of running millions of steps.
  double dt_min_s = 2.0e-3 / 128.0;
  // At the code frequency f_cut: the HHT period elongation of the scene's
  // scheme stays below this (see bound 1).
  double max_period_error = 0.0025;
  HhtParameters hht = HhtParameters::from_alpha(-0.05);
  double max_travel_fraction_of_element = 0.25;  // of the shortest rail element, per step
  double contact_steps_per_period = 10.0;        // at the Hertz contact frequency f_H
  // Multibody trains on a profile: steps while a wheel crosses the profile's
  // shortest feature (planning/track_feature.hpp; bound 4), more for a
  // feature that throws the wheel off the rail (its profile acceleration
  // v^2 r'' above impact_acceleration_mps2: loss of contact and re-impact).
  double track_steps_per_feature = 40.0;
  double impact_steps_per_feature = 150.0;
  double impact_acceleration_mps2 = 500.0;
  // Rigid contact: steps while a wheel crosses the shortest rail element (bound 5).
  double rigid_steps_per_element = 12.0;
};

struct TimeStepBound {
  std::string name;   // "code frequency", "wheel travel", "contact frequency", "track profile", "rigid contact"
  double dt_s = 0.0;  // largest admissible step
  std::string detail;  // "f_cut = max(30, 1.5 f0 = 7.5, f3 = 45.0) = 45.0 Hz at 20 steps/period"
};

struct TimeStepChoice {
  double dt_s = 0.0;          // dt_max / 2^ladder_k, at least dt_min
  int ladder_k = 0;
  double required_dt_s = 0.0;  // the smallest bound
  std::string binding;         // name of that bound
  std::vector<TimeStepBound> bounds;
  // For the job record: every bound with its numbers, the binding one, the
  // ladder rung, e.g. "f_cut = ... = 36.0 Hz at 20 steps/period needs
  // 1.39e-03 s; wheel travel 0.25 x 0.600 m element at 83.3 m/s needs
  // 1.80e-03 s; binding: code frequency; ladder 2.0e-03 s / 2^1 = 1.0e-03 s".
  std::string reason;
};

// f0_hz, f3_hz: first bending and third frequency of the deck (0 when
// unknown: f_cut is then 30 Hz or what the other is). contact: the scene's
// contact options (ignored for moving forces). speed_mps >= 0. Throws
// std::invalid_argument for negative or non-finite arguments or a policy
// value <= 0 (they are computed, not user input: the study is validated
// before planning).
// profile: the scene's track irregularity (null: a perfect track).
TimeStepChoice choose_time_step(const StructureModel& structure, const Train& train, double speed_mps,
                                const ContactOptions& contact, double f0_hz, double f3_hz,
                                const TimeStepPolicy& policy = {}, const Irregularity* profile = nullptr);

// Largest omega*dt at which the HHT period elongation is <= max_period_error.
double max_omega_dt(const HhtParameters& hht, double max_period_error);
// Shortest element of all rail lines, m.
double shortest_rail_element_m(const StructureModel& structure);
// Highest linearized Hertz frequency of the train's wheels, Hz; 0 for moving
// forces or a rigid contact.
double highest_contact_frequency_hz(const Train& train, const ContactOptions& contact);

}  // namespace railvsi

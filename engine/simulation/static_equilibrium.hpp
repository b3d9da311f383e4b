#pragma once
// Static equilibrium of train and structure under gravity at t = 0, with
// the contact law's static compression, so that the run starts without a
// drop transient. Structure self-weight is excluded: deck displacements are
// measured from the equilibrium of the structure under its own weight.
#include <optional>
#include <vector>

#include "model/rail_line.hpp"
#include "simulation/scene.hpp"
#include "simulation/train_layout.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

struct StaticState {
  Vector u_s;  // structure, in the coordinates of the operator it was solved with
  Vector u_v;  // stacked vehicles
  Vector P;    // contact forces (= static wheel loads)
};

// Where each contact is at front position x: a Hermite row on its rail line,
// or empty on the rigid path.
std::vector<std::optional<RailContactRow>> locate_contacts(const StructureModel& s,
                                                           const TrainLayout& layout,
                                                           double front_x_m);

// `statics` is the static stiffness operator of the backend the run
// integrates (StructureOperator::static_operator). Throws InputError if the
// structure is a mechanism or a vehicle is not carried by its wheels.
StaticState static_equilibrium(const Scene& scene, const TrainLayout& layout, double front_x_m,
                               const StructureOperator& statics);

// Wheel loads of one vehicle standing on a rigid, level track: what the
// vehicle becomes when a scene asks for it as moving forces. Throws
// InputError if the vehicle is not carried by its wheels.
Vector static_wheel_loads_on_rigid_track(const VehicleModel& vehicle);

// Axle loads of a train: its moving forces, or each wheel's static load on
// a rigid, level track, ordered by offset (what "as": "moving_forces" gives).
std::vector<MovingForce> axle_loads(const Train& train);

// Adds the downward moving-force loads of the scene's train with its first
// axle at front_x_m, split over ContactOptions::rail_lines, to f (in the
// structure coordinates `coords`).
void add_moving_force_loads(const Scene& scene, double front_x_m, Vector& f, const StructureCoordinates& coords);

}  // namespace railvsi

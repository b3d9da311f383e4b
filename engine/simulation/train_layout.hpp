#pragma once
// The train flattened for the solvers: the vehicles' DOFs stacked into one
// vector, and one contact per wheel with its law. Built once per run.
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "integration/hht.hpp"
#include "simulation/scene.hpp"

namespace railvsi {

struct VehicleInstance {
  const VehicleModel* model = nullptr;
  int first_dof = 0;
  double offset_m = 0.0;
  int type = 0;  // index into TrainLayout::types
};

struct ContactSpec {
  int vehicle = 0;
  int local_dof = 0;   // in the vehicle's matrices
  int global_dof = 0;  // in the stacked vehicle vector
  int local_wheel = 0;
  double offset_m = 0.0;  // behind the train's first axle
  int rail_line = 0;
  int rails_per_wheel = 1;
  std::shared_ptr<const ContactLaw> law;  // linearized at the static load once it is known
};

// "v<vehicle>_w<wheel>", 1-based: the name of a wheel in histories and summaries.
std::string wheel_name(const ContactSpec& c);

struct TrainLayout {
  TrainLayout(const Train& train, const ContactOptions& contact);

  std::vector<const VehicleModel*> types;  // distinct vehicle models
  std::vector<VehicleInstance> vehicles;
  std::vector<ContactSpec> contacts;
  int num_vehicle_dofs = 0;
  Vector gravity_load_N;  // stacked

  // Position along the track of something `offset_m` behind the first axle.
  static double position_m(double front_x_m, double offset_m) { return front_x_m - offset_m; }
};

// Per car body (a vehicle and its DOF), the contacts of the wheels under
// it: its acceleration counts while one of them is in the evaluation window.
// Per body, not per vehicle: an articulated rake is one vehicle 170 m long,
// whose far bodies ride plain track while its first wheels cross the bridge.
// In the order of the histories' body_names.
struct BodyWheels {
  std::size_t vehicle = 0;
  int dof = 0;
  std::vector<Eigen::Index> contacts;
};
std::vector<BodyWheels> body_wheels(const TrainLayout& layout);

// Per vehicle type and time step: the dense factor of K_bar_v and its
// flexibility at the wheels.
struct VehicleOperator {
  Eigen::LDLT<DenseMatrix> factor;
  DenseMatrix wheel_columns;  // K_bar_v^-1 E^T (n_dofs x n_wheels)
  DenseMatrix wheel_flexibility;  // E K_bar_v^-1 E^T
  // K_bar_v^-1 M E^T and K_bar_v^-1 C E^T: how the wheels' kinematic
  // acceleration and velocity under rigid contact move the vehicle.
  DenseMatrix mass_columns, damping_columns;
};

std::vector<VehicleOperator> make_vehicle_operators(const TrainLayout& layout,
                                                    const HhtCoefficients& h);

// K_bar_v = c0 M + (1+alpha) c3 C + (1+alpha) K of one vehicle.
DenseMatrix vehicle_effective_matrix(const VehicleModel& v, const HhtCoefficients& h);

}  // namespace railvsi

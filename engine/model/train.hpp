#pragma once
// A train: either a list of axle loads (moving forces, e.g. HSLM) or
// multibody vehicles placed along the train. Offsets are measured behind the
// first axle of the train.
#include <memory>
#include <string>
#include <vector>

#include "model/vehicle_model.hpp"

namespace railvsi {

struct MovingForce {
  double offset_m = 0.0;
  double load_N = 0.0;  // downward
};

struct TrainVehicle {
  std::shared_ptr<const VehicleModel> model;
  double offset_m = 0.0;  // of the vehicle's first axle
};

struct Train {
  std::string name;
  std::vector<MovingForce> moving_forces;
  std::vector<TrainVehicle> vehicles;
  // HSLM-A coach length D (EN 1991-2 Annex E) or HSLM-B spacing d, the
  // regular length whose passages excite resonance at v = f0 D / i; 0 for
  // other trains.
  double coach_length_m = 0.0;

  bool is_moving_forces() const { return vehicles.empty(); }
  // Distance from the first to the last axle.
  double length_m() const;
  int num_axles() const;
};

}  // namespace railvsi

#pragma once
// Pitch-plane multibody vehicles: rigid bodies with bounce (and pitch)
// joined by spring-dashpots, wheelsets carrying the wheels. A conventional
// car is two bogies under one body; an articulated set shares a bogie
// between consecutive bodies.
#include <memory>
#include <string>
#include <vector>

#include "model/vehicle_model.hpp"

namespace railvsi {

struct SpringDamper {
  double k_N_per_m = 0.0;
  double c_Ns_per_m = 0.0;
};

// One car of the 2D template. Offsets are behind the car's first axle.
// Conventions (stated in every train file): primary values per wheelset
// (both axle boxes of both sides together), secondary values per bogie.
struct Car2dOptions {
  std::string name = "car";
  double body_mass_kg = 0.0;
  double body_pitch_inertia_kgm2 = 0.0;
  double bogie_mass_kg = 0.0;
  double bogie_pitch_inertia_kgm2 = 0.0;
  double wheelset_mass_kg = 0.0;
  double bogie_spacing_m = 0.0;  // between bogie centres
  double axle_spacing_m = 0.0;   // within a bogie
  SpringDamper primary;          // per wheelset
  SpringDamper secondary;        // per bogie
  double wheel_radius_m = 0.46;
};

// Throws InputError with paths relative to the car's JSON object.
std::shared_ptr<const VehicleModel> make_car_2d(const Car2dOptions& options);

// An articulated set: `bodies` car bodies in a row on bodies + 1 bogies,
// each inner (Jacobs) bogie shared by the two bodies whose ends meet above
// it. Every body, bogie and wheelset is as in `car`, with bogie_spacing_m the
// distance between consecutive bogie centres (the body length between
// articulations). Secondary values are per body end: each body rests on the
// bogie at either end through one such spring-dashpot, so a shared bogie
// carries two of them (one per body, both at the bogie centre). The bodies
// are not coupled to each other directly. Every body is a body of interest.
// Throws InputError with paths relative to the set's JSON object.
struct Articulated2dOptions {
  Car2dOptions car;
  int bodies = 2;
};
std::shared_ptr<const VehicleModel> make_articulated_2d(const Articulated2dOptions& options);

// A general planar multibody assembler (used by the templates above).
class Multibody2d {
 public:
  // Returns the body index. pitch=false for wheelsets (bounce only).
  int add_body(double mass_kg, double pitch_inertia_kgm2, double offset_m, bool pitch);
  // Spring-dashpot between body a and body b at the longitudinal offset x_m.
  void connect(int a, int b, double offset_m, const SpringDamper& sd);
  int add_wheel(int body, double radius_m);
  void mark_body(int body) { body_of_interest_.push_back(body); }
  std::shared_ptr<const VehicleModel> build(std::string name) const;

 private:
  struct Body { double mass, inertia, offset; bool pitch; int dof; };
  struct Link { int a, b; double offset; SpringDamper sd; };
  std::vector<Body> bodies_;
  std::vector<Link> links_;
  std::vector<std::pair<int, double>> wheels_;
  std::vector<int> body_of_interest_;
  int n_ = 0;
};

}  // namespace railvsi

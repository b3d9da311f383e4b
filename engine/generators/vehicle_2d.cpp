#include "generators/vehicle_2d.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

int Multibody2d::add_body(double mass_kg, double pitch_inertia_kgm2, double offset_m, bool pitch) {
  bodies_.push_back({mass_kg, pitch_inertia_kgm2, offset_m, pitch, n_});
  n_ += pitch ? 2 : 1;
  return static_cast<int>(bodies_.size()) - 1;
}

void Multibody2d::connect(int a, int b, double offset_m, const SpringDamper& sd) {
  links_.push_back({a, b, offset_m, sd});
}

int Multibody2d::add_wheel(int body, double radius_m) {
  wheels_.emplace_back(body, radius_m);
  return static_cast<int>(wheels_.size()) - 1;
}

std::shared_ptr<const VehicleModel> Multibody2d::build(std::string name) const {
  DenseMatrix K = DenseMatrix::Zero(n_, n_), M = K, C = K;
  Vector gravity = Vector::Zero(n_);
  for (const Body& b : bodies_) {
    M(b.dof, b.dof) = b.mass;
    gravity[b.dof] = 1.0;
    if (b.pitch) M(b.dof + 1, b.dof + 1) = b.inertia;
  }
  // Vertical displacement of a body at offset x (positive backwards) with
  // pitch theta positive nose-up: z - theta * (x - x_body).
  for (const Link& l : links_) {
    Vector r = Vector::Zero(n_);
    const Body& A = bodies_[l.a];
    const Body& B = bodies_[l.b];
    r[A.dof] += 1.0;
    if (A.pitch) r[A.dof + 1] -= (l.offset - A.offset);
    r[B.dof] -= 1.0;
    if (B.pitch) r[B.dof + 1] += (l.offset - B.offset);
    K += l.sd.k_N_per_m * r * r.transpose();
    C += l.sd.c_Ns_per_m * r * r.transpose();
  }
  std::vector<Wheel> wheels;
  for (const auto& [body, radius] : wheels_)
    wheels.push_back({bodies_[body].dof, bodies_[body].offset, radius, 0});
  std::vector<int> body_dofs;
  for (int b : body_of_interest_) body_dofs.push_back(bodies_[b].dof);
  return std::make_shared<const VehicleModel>(std::move(name), K, M, C, gravity, std::move(wheels),
                                              std::move(body_dofs));
}

namespace {

void check_car_2d(const Car2dOptions& o) {
  const std::pair<const char*, double> positive[] = {
      {"/car_body/mass_kg", o.body_mass_kg},
      {"/car_body/pitch_inertia_kgm2", o.body_pitch_inertia_kgm2},
      {"/bogie/mass_kg", o.bogie_mass_kg},
      {"/bogie/pitch_inertia_kgm2", o.bogie_pitch_inertia_kgm2},
      {"/wheelset/mass_kg", o.wheelset_mass_kg},
      {"/bogie_spacing_m", o.bogie_spacing_m},
      {"/axle_spacing_m", o.axle_spacing_m},
      {"/primary/k_N_per_m", o.primary.k_N_per_m},
      {"/secondary/k_N_per_m", o.secondary.k_N_per_m},
      {"/wheelset/radius_m", o.wheel_radius_m}};
  for (const auto& [path, value] : positive)
    if (!(value > 0.0)) throw InputError(path, fmt::format("must be > 0 (got {})", value));
  if (!(o.primary.c_Ns_per_m >= 0.0)) throw InputError("/primary/c_Ns_per_m", "must be >= 0");
  if (!(o.secondary.c_Ns_per_m >= 0.0)) throw InputError("/secondary/c_Ns_per_m", "must be >= 0");
  if (!(o.bogie_spacing_m > o.axle_spacing_m))
    throw InputError("/bogie_spacing_m", "must exceed axle_spacing_m");
}

// Bodies 0..n-1 on bogies 0..n: body i rests on bogies i and i+1. A car is
// the case n = 1.
std::shared_ptr<const VehicleModel> bodies_on_bogies(const Car2dOptions& o, int n) {
  Multibody2d mb;
  const double a = o.axle_spacing_m, lb = o.bogie_spacing_m;
  std::vector<int> bodies;
  for (int i = 0; i < n; ++i) {
    bodies.push_back(mb.add_body(o.body_mass_kg, o.body_pitch_inertia_kgm2, 0.5 * a + (i + 0.5) * lb, true));
    mb.mark_body(bodies.back());
  }
  for (int j = 0; j <= n; ++j) {
    const double bogie_x = 0.5 * a + j * lb;
    const int bogie = mb.add_body(o.bogie_mass_kg, o.bogie_pitch_inertia_kgm2, bogie_x, true);
    for (int i : {j - 1, j})
      if (i >= 0 && i < n) mb.connect(bodies[static_cast<std::size_t>(i)], bogie, bogie_x, o.secondary);
    for (double axle_x : {bogie_x - 0.5 * a, bogie_x + 0.5 * a}) {
      const int ws = mb.add_body(o.wheelset_mass_kg, 0.0, axle_x, false);
      mb.connect(bogie, ws, axle_x, o.primary);
      mb.add_wheel(ws, o.wheel_radius_m);
    }
  }
  return mb.build(o.name);
}

}  // namespace

std::shared_ptr<const VehicleModel> make_car_2d(const Car2dOptions& o) {
  check_car_2d(o);
  return bodies_on_bogies(o, 1);
}

std::shared_ptr<const VehicleModel> make_articulated_2d(const Articulated2dOptions& o) {
  if (o.bodies < 2)
    throw InputError("/bodies", fmt::format("an articulated set has at least 2 bodies (got {}); use car-2d for one",
                                            o.bodies));
  check_car_2d(o.car);
  return bodies_on_bogies(o.car, o.bodies);
}

}  // namespace railvsi

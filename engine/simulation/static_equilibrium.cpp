#include "simulation/static_equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "solver/substructured_flexibility.hpp"

namespace railvsi {

std::vector<std::optional<RailContactRow>> locate_contacts(const StructureModel& s,
                                                           const TrainLayout& layout,
                                                           double front_x_m) {
  std::vector<std::optional<RailContactRow>> rows;
  rows.reserve(layout.contacts.size());
  for (const ContactSpec& c : layout.contacts) {
    const double x = TrainLayout::position_m(front_x_m, c.offset_m);
    rows.push_back(s.rails()[static_cast<std::size_t>(c.rail_line)].locate(x));
  }
  return rows;
}

Vector static_wheel_loads_on_rigid_track(const VehicleModel& vehicle) {
  // [K -E^T; -E 0] [u; P] = [F_g; 0]: wheels held at zero displacement.
  const Eigen::Index n = vehicle.num_dofs();
  const auto nw = static_cast<Eigen::Index>(vehicle.wheels().size());
  DenseMatrix J = DenseMatrix::Zero(n + nw, n + nw);
  J.topLeftCorner(n, n) = vehicle.K();
  for (Eigen::Index w = 0; w < nw; ++w) {
    J(vehicle.wheels()[w].dof, n + w) = -1.0;
    J(n + w, vehicle.wheels()[w].dof) = -1.0;
  }
  Vector rhs = Vector::Zero(n + nw);
  rhs.head(n) = vehicle.gravity_load_N();
  const Eigen::FullPivLU<DenseMatrix> lu(J);
  if (!lu.isInvertible())
    throw InputError("", fmt::format("vehicle '{}' is not statically supported by its wheels",
                                     vehicle.name()));
  return lu.solve(rhs).tail(nw);
}

std::vector<MovingForce> axle_loads(const Train& train) {
  if (train.is_moving_forces()) return train.moving_forces;
  std::vector<MovingForce> out;
  for (const TrainVehicle& v : train.vehicles) {
    const Vector loads = static_wheel_loads_on_rigid_track(*v.model);
    for (std::size_t w = 0; w < v.model->wheels().size(); ++w)
      out.push_back({v.offset_m + v.model->wheels()[w].offset_m, loads[static_cast<Eigen::Index>(w)]});
  }
  std::stable_sort(out.begin(), out.end(), [](const MovingForce& a, const MovingForce& b) { return a.offset_m < b.offset_m; });
  return out;
}

void add_moving_force_loads(const Scene& scene, double front_x_m, Vector& f, const StructureCoordinates& coords) {
  const auto& rails = scene.analysis.contact.rail_lines;
  const double share = 1.0 / static_cast<double>(rails.size());
  for (const MovingForce& m : scene.train.moving_forces)
    for (int r : rails) {
      const auto row = scene.structure->rails()[static_cast<std::size_t>(r)].locate(
          TrainLayout::position_m(front_x_m, m.offset_m));
      if (!row) continue;
      for (int k = 0; k < 4; ++k)
        coords.add(row->dof[k], -share * row->weight[k] * m.load_N, f);
    }
}

namespace {

constexpr double kNominalLoad_N = 1.0e5;
constexpr int kStaticNewtonIterations = 60;

// The static state is set up before the run: a failed solve is a scene that
// cannot be run.
void solve_static(const StructureOperator& op, const Vector& f, Vector& u, SolveWorkspace& ws) {
  if (f.squaredNorm() == 0.0) return;
  const Status st = op.solve(f, u, ws);
  if (!st.ok()) throw InputError("/structure", "static deflection under the train: " + st.message());
  if (!u.allFinite()) throw InputError("/structure", "static deflection under the train is not finite");
}

// Moving forces: the loads at t = 0, structure only.
StaticState moving_force_statics(const Scene& scene, const StructureOperator& op, double front_x_m) {
  const StructureCoordinates coords = op.coordinates(*scene.structure);
  StaticState st;
  Vector f = Vector::Zero(coords.size());
  add_moving_force_loads(scene, front_x_m, f, coords);
  auto ws = op.make_workspace();
  st.u_s = Vector::Zero(coords.size());
  solve_static(op, f, st.u_s, *ws);
  return st;
}

}  // namespace

StaticState static_equilibrium(const Scene& scene, const TrainLayout& layout, double front_x_m,
                               const StructureOperator& op) {
  const StructureModel& s = *scene.structure;
  if (scene.train.is_moving_forces()) return moving_force_statics(scene, op, front_x_m);

  const auto rows = locate_contacts(s, layout, front_x_m);
  const auto nc = static_cast<Eigen::Index>(layout.contacts.size());
  const Eigen::Index nv = layout.num_vehicle_dofs;

  // Static structure flexibility at the DOFs under the wheels.
  std::vector<int> dofs;
  for (const auto& row : rows)
    if (row)
      for (int d : row->dof)
        if (d >= 0 && std::find(dofs.begin(), dofs.end(), d) == dofs.end()) dofs.push_back(d);
  auto ws = op.make_workspace();
  // The track substructure is exact for the FE operator (it inverts K);
  // the modal one's flexibility is that of its modes.
  const bool fe = !op.coordinates(s).modal();
  DenseMatrix F = dofs.empty()   ? DenseMatrix()
                  : fe ? substructured_flexibility(op, s.K(), s, dofs, *ws)
                       : op.flexibility_block(dofs, *ws);
  // The modes' static correction (rail_residual_flexibility()) makes the
  // modal flexibility the exact one at the rail DOFs, as the run's contact
  // sees it; not on the rigid path, whose run leaves it out.
  const DenseMatrix* residual = op.rail_residual_flexibility();
  if (residual && !layout.contacts.empty() && !layout.contacts.front().law->is_constraint())
    for (std::size_t i = 0; i < dofs.size(); ++i)
      for (std::size_t j = 0; j < dofs.size(); ++j)
        F(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) +=
            (*residual)(op.rail_index(dofs[i]), op.rail_index(dofs[j]));
  const auto local = [&](int d) { return std::find(dofs.begin(), dofs.end(), d) - dofs.begin(); };
  DenseMatrix As = DenseMatrix::Zero(nc, nc);
  for (Eigen::Index c = 0; c < nc; ++c)
    for (Eigen::Index e = 0; e < nc; ++e) {
      if (!rows[c] || !rows[e]) continue;
      double a = 0.0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          if (rows[c]->dof[i] >= 0 && rows[e]->dof[j] >= 0)
            a += rows[c]->weight[i] * rows[e]->weight[j] * F(local(rows[c]->dof[i]), local(rows[e]->dof[j]));
      As(c, e) = a;
    }
  Vector r = Vector::Zero(nc);
  for (Eigen::Index c = 0; c < nc; ++c)
    if (scene.irregularity)
      r[c] = scene.irregularity->at(TrainLayout::position_m(front_x_m, layout.contacts[c].offset_m));

  DenseMatrix Kv = DenseMatrix::Zero(nv, nv);
  for (const VehicleInstance& v : layout.vehicles)
    Kv.block(v.first_dof, v.first_dof, v.model->num_dofs(), v.model->num_dofs()) = v.model->K();

  // Newton on z = [u_v; P]:
  //   K_v u_v - E^T P - F_g = 0
  //   -A_s P + r - E u_v - h(P) = 0   (h: compression of the law, 0 if rigid)
  // The first iteration from z = 0 is linear: rigid contacts, or compliant
  // ones as linear springs stiffened at a nominal 100 kN (a start with every
  // load positive; it also splits a wheelset's load between two rails on a
  // rigid path, where a rigid split is indeterminate).
  Vector z = Vector::Zero(nv + nc), R(nv + nc);
  const auto& laws = layout.contacts;
  bool converged = false;
  double last_step_norm = 0.0;
  for (int it = 0; it < kStaticNewtonIterations; ++it) {
    const bool compliant = it > 0;
    const Vector u_v = z.head(nv), P = z.tail(nc);
    DenseMatrix J = DenseMatrix::Zero(nv + nc, nv + nc);
    J.topLeftCorner(nv, nv) = Kv;
    J.bottomRightCorner(nc, nc) = -As;
    R.head(nv) = Kv * u_v - layout.gravity_load_N;
    R.tail(nc) = -As * P + r;
    for (Eigen::Index c = 0; c < nc; ++c) {
      const int g = laws[c].global_dof;
      J(g, nv + c) -= 1.0;
      J(nv + c, g) -= 1.0;
      R[g] -= P[c];
      R[nv + c] -= u_v[g];
      if (compliant) {
        R[nv + c] -= laws[c].law->compression(P[c]);
        J(nv + c, nv + c) -= laws[c].law->compliance(P[c]);
      } else if (!laws[c].law->is_constraint()) {
        const double nominal_compliance = laws[c].law->compression(kNominalLoad_N) / kNominalLoad_N;
        R[nv + c] -= nominal_compliance * P[c];
        J(nv + c, nv + c) -= nominal_compliance;
      }
    }
    // Equilibrate: stiffness rows (~1e6 N/m) and compliance rows (~1e-9 m/N)
    // differ by 15 orders, which would fool the rank test.
    Vector d(nv + nc);
    for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = J(i, i) != 0.0 ? 1.0 / std::sqrt(std::abs(J(i, i))) : 1.0;
    const Eigen::FullPivLU<DenseMatrix> lu(d.asDiagonal() * J * d.asDiagonal());
    if (!lu.isInvertible())
      throw InputError("/train", "the train is not statically supported by its wheels (the static "
                                 "equilibrium matrix is singular: a vehicle DOF has no stiffness "
                                 "path to a wheel)");
    const Vector dz = d.asDiagonal() * lu.solve(-(d.asDiagonal() * R)).eval();
    // Keep the loads compressive while the compliant iteration settles.
    double step = 1.0;
    if (compliant)
      while (step > 1e-6 && ((z.tail(nc) + step * dz.tail(nc)).array() <= 0.0).any()) step *= 0.5;
    z += step * dz;
    if (!compliant) {
      for (Eigen::Index c = 0; c < nc; ++c)
        if (!(z[nv + c] > 0.0))
          throw InputError("/train",
                           fmt::format("wheel {} of vehicle {} carries no static load ({:.1f} N): "
                                       "the vehicle does not rest on its wheels",
                                       laws[c].local_wheel, laws[c].vehicle, z[nv + c]));
      if (laws.empty() || laws.front().law->is_constraint()) {
        converged = true;
        break;
      }
    } else if ((last_step_norm = step * dz.norm()) <= 1e-13 * z.norm()) {
      converged = true;
      break;
    }
  }
  // Round-off may keep the last correction just above 1e-13: accept 1e-9.
  if (!converged && last_step_norm <= 1e-9 * z.norm()) converged = true;
  if (!converged || !z.allFinite())
    throw InputError("/train", fmt::format("the static equilibrium of the train on the structure did not converge "
                                           "in {} Newton iterations (last correction {:.3e} of {:.3e})",
                                           kStaticNewtonIterations, last_step_norm, z.norm()));
  StaticState st;
  st.u_v = z.head(nv);
  st.P = z.tail(nc);
  const StructureCoordinates coords = op.coordinates(s);
  Vector f = Vector::Zero(coords.size());
  add_rail_loads(rows, st.P, 1.0, f, coords);
  st.u_s = Vector::Zero(coords.size());
  solve_static(op, f, st.u_s, *ws);
  return st;
}

}  // namespace railvsi

#include "simulation/train_layout.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

TrainLayout::TrainLayout(const Train& train, const ContactOptions& contact) {
  int next_dof = 0;
  for (const TrainVehicle& tv : train.vehicles) {
    const VehicleModel* model = tv.model.get();
    auto it = std::find(types.begin(), types.end(), model);
    const int type = static_cast<int>(it - types.begin());
    if (it == types.end()) types.push_back(model);
    const int vehicle = static_cast<int>(vehicles.size());
    vehicles.push_back({model, next_dof, tv.offset_m, type});
    for (std::size_t w = 0; w < model->wheels().size(); ++w)
      for (int rail : contact.rail_lines) {
      const Wheel& wheel = model->wheels()[w];
      ContactSpec c;
      c.vehicle = vehicle;
      c.local_dof = wheel.dof;
      c.global_dof = next_dof + wheel.dof;
      c.local_wheel = static_cast<int>(w);
      c.offset_m = tv.offset_m + wheel.offset_m;
      c.rail_line = rail;
      c.rails_per_wheel = static_cast<int>(contact.rail_lines.size());
      c.law = make_contact_law(contact, {wheel.radius_m, c.rails_per_wheel});
      contacts.push_back(c);
      }
    next_dof += model->num_dofs();
  }
  num_vehicle_dofs = next_dof;
  gravity_load_N = Vector::Zero(next_dof);
  for (const VehicleInstance& v : vehicles)
    gravity_load_N.segment(v.first_dof, v.model->num_dofs()) = v.model->gravity_load_N();
}

std::string wheel_name(const ContactSpec& c) {
  if (c.rails_per_wheel > 1) return fmt::format("v{}_w{}_r{}", c.vehicle + 1, c.local_wheel + 1, c.rail_line + 1);
  return fmt::format("v{}_w{}", c.vehicle + 1, c.local_wheel + 1);
}

std::vector<BodyWheels> body_wheels(const TrainLayout& layout) {
  std::vector<BodyWheels> out;
  const auto nc = static_cast<Eigen::Index>(layout.contacts.size());
  // The wheels under a body: two couplings away (body, bogie, wheel).
  constexpr int kBodyToWheel = 2;
  for (std::size_t v = 0; v < layout.vehicles.size(); ++v) {
    const VehicleModel& model = *layout.vehicles[v].model;
    for (int d : model.body_dofs()) {
      BodyWheels b{v, d, {}};
      const std::vector<int> near = model.coupled_dofs(d, kBodyToWheel);
      for (Eigen::Index c = 0; c < nc; ++c) {
        const ContactSpec& cs = layout.contacts[static_cast<std::size_t>(c)];
        if (cs.vehicle == static_cast<int>(v) && std::find(near.begin(), near.end(), cs.local_dof) != near.end())
          b.contacts.push_back(c);
      }
      // A body no wheel reaches within two couplings (a model of another
      // shape) counts with every wheel of its vehicle.
      if (b.contacts.empty())
        for (Eigen::Index c = 0; c < nc; ++c)
          if (layout.contacts[static_cast<std::size_t>(c)].vehicle == static_cast<int>(v)) b.contacts.push_back(c);
      out.push_back(std::move(b));
    }
  }
  return out;
}

DenseMatrix vehicle_effective_matrix(const VehicleModel& v, const HhtCoefficients& h) {
  return h.mass_factor() * v.M() + h.damping_factor() * v.C() + h.stiffness_factor() * v.K();
}

std::vector<VehicleOperator> make_vehicle_operators(const TrainLayout& layout,
                                                    const HhtCoefficients& h) {
  std::vector<VehicleOperator> ops;
  for (const VehicleModel* model : layout.types) {
    VehicleOperator op;
    op.factor.compute(vehicle_effective_matrix(*model, h));
    // K_bar_v of a vehicle with mass on every DOF is positive definite.
    if (op.factor.info() != Eigen::Success || !op.factor.isPositive())
      throw InputError("/train", fmt::format("vehicle '{}': its effective matrix (M, C, K at this dt) is not "
                                             "positive definite, LDLT factorization failed",
                                             model->name()));
    const auto nw = static_cast<Eigen::Index>(model->wheels().size());
    DenseMatrix Et = DenseMatrix::Zero(model->num_dofs(), nw);
    for (Eigen::Index w = 0; w < nw; ++w) Et(model->wheels()[w].dof, w) = 1.0;
    op.wheel_columns = op.factor.solve(Et);
    op.wheel_flexibility = Et.transpose() * op.wheel_columns;
    op.mass_columns = op.factor.solve(model->M() * Et);
    op.damping_columns = op.factor.solve(model->C() * Et);
    if (!op.wheel_columns.allFinite())
      throw InputError("/train", fmt::format("vehicle '{}': its wheel flexibility is not finite", model->name()));
    ops.push_back(std::move(op));
  }
  return ops;
}

}  // namespace railvsi

#include "model/vehicle_model.hpp"

#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {

VehicleModel::VehicleModel(std::string name, DenseMatrix K, DenseMatrix M, DenseMatrix C,
                           Vector gravity_dofs, std::vector<Wheel> wheels,
                           std::optional<std::vector<int>> body_dofs)
    : name_(std::move(name)), K_(std::move(K)), M_(std::move(M)), C_(std::move(C)),
      wheels_(std::move(wheels)) {
  const auto n = K_.rows();
  if (n == 0 || K_.cols() != n || M_.rows() != n || M_.cols() != n)
    throw InputError("/matrices", "vehicle K and M must be square and of the same size");
  if (C_.size() == 0) C_ = DenseMatrix::Zero(n, n);
  if (C_.rows() != n || C_.cols() != n) throw InputError("/matrices/C", "vehicle C size differs from K");
  if (gravity_dofs.size() != n)
    throw InputError("/vertical_dofs", "one gravity flag per DOF is needed");
  const auto asym = [](const DenseMatrix& A) {
    return (A - A.transpose()).cwiseAbs().maxCoeff() > 1e-10 * std::max(1.0, A.cwiseAbs().maxCoeff());
  };
  if (asym(K_)) throw InputError("/matrices/K", "vehicle stiffness matrix is not symmetric");
  if (asym(M_)) throw InputError("/matrices/M", "vehicle mass matrix is not symmetric");
  if (asym(C_)) throw InputError("/matrices/C", "vehicle damping matrix is not symmetric");
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(M_(i, i) >= 0.0))
      throw InputError(fmt::format("/matrices/M/{}/{}", i, i), "vehicle mass must be >= 0");
  if (wheels_.empty()) throw InputError("/wheels", "a vehicle needs at least one wheel");
  for (std::size_t w = 0; w < wheels_.size(); ++w) {
    if (wheels_[w].dof < 0 || wheels_[w].dof >= n)
      throw InputError(fmt::format("/wheels/{}/dof", w), "wheel DOF outside the vehicle");
    if (!(wheels_[w].radius_m > 0.0))
      throw InputError(fmt::format("/wheels/{}/radius_m", w), "wheel radius must be > 0");
  }
  gravity_load_ = -kGravity_mps2 * (M_ * gravity_dofs);
  total_mass_ = gravity_dofs.dot(M_ * gravity_dofs);
  if (!(total_mass_ > 0.0)) throw InputError("/matrices/M", "vehicle has no translational mass");
  if (body_dofs) {
    body_dofs_ = std::move(*body_dofs);
    for (std::size_t k = 0; k < body_dofs_.size(); ++k)
      if (body_dofs_[k] < 0 || body_dofs_[k] >= n)
        throw InputError(fmt::format("/body_dofs/{}", k),
                         fmt::format("DOF {} outside the vehicle (0..{})", body_dofs_[k], n - 1));
    return;
  }
  // By default every translational DOF that is not a wheel is "body".
  for (Eigen::Index i = 0; i < n; ++i) {
    bool wheel = false;
    for (const Wheel& w : wheels_) wheel = wheel || w.dof == i;
    if (gravity_dofs[i] != 0.0 && !wheel) body_dofs_.push_back(static_cast<int>(i));
  }
}

std::vector<int> VehicleModel::coupled_dofs(int dof, int links) const {
  const int n = num_dofs();
  std::vector<int> reached{dof}, distance(static_cast<std::size_t>(n), -1);
  distance[static_cast<std::size_t>(dof)] = 0;
  for (std::size_t next = 0; next < reached.size(); ++next) {
    const int i = reached[next];
    if (distance[static_cast<std::size_t>(i)] == links) continue;
    for (int j = 0; j < n; ++j)
      if (j != i && distance[static_cast<std::size_t>(j)] < 0 &&
          (K_(i, j) != 0.0 || C_(i, j) != 0.0 || M_(i, j) != 0.0)) {
        distance[static_cast<std::size_t>(j)] = distance[static_cast<std::size_t>(i)] + 1;
        reached.push_back(j);
      }
  }
  return reached;
}

}  // namespace railvsi

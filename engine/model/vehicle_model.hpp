#pragma once
// A vehicle (or an articulated set of car bodies sharing bogies): small,
// dense, linear. Immutable once built; one instance may be shared by every
// car of the same type in a train.
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace railvsi {

struct Wheel {
  int dof = -1;          // vertical DOF of the wheelset in the vehicle's matrices
  double offset_m = 0.0;  // behind the vehicle's first axle (positive backwards)
  double radius_m = 0.46;
  int rail_line = 0;
};

class VehicleModel {
 public:
  // gravity_dofs[i] = 1 for a vertical translation, 0 for a rotation: the
  // gravity load is -g * M * gravity_dofs. body_dofs: the DOFs whose
  // accelerations are car-body accelerations; by default every
  // translational DOF that is not a wheel. Throws InputError on bad sizes,
  // asymmetric matrices or non-positive mass.
  VehicleModel(std::string name, DenseMatrix K, DenseMatrix M, DenseMatrix C, Vector gravity_dofs,
               std::vector<Wheel> wheels, std::optional<std::vector<int>> body_dofs = std::nullopt);

  const std::string& name() const { return name_; }
  int num_dofs() const { return static_cast<int>(K_.rows()); }
  const DenseMatrix& K() const { return K_; }
  const DenseMatrix& M() const { return M_; }
  const DenseMatrix& C() const { return C_; }
  const std::vector<Wheel>& wheels() const { return wheels_; }
  // External load: gravity on every translational DOF.
  const Vector& gravity_load_N() const { return gravity_load_; }
  double total_mass_kg() const { return total_mass_; }
  // Indices of the DOFs that the car-body acceleration envelope looks at.
  const std::vector<int>& body_dofs() const { return body_dofs_; }
  // DOFs reached from `dof` through at most `links` couplings (non-zero
  // off-diagonal terms of K, C or M): with links = 4 from a wheel, the
  // wheels under the same car body (wheel, bogie, body, bogie, wheel).
  std::vector<int> coupled_dofs(int dof, int links) const;

 private:
  std::string name_;
  DenseMatrix K_, M_, C_;
  std::vector<Wheel> wheels_;
  Vector gravity_load_;
  double total_mass_ = 0.0;
  std::vector<int> body_dofs_;
};

}  // namespace railvsi

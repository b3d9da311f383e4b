#include "solver/residual_flexibility.hpp"

#include "solver/cholmod_operator.hpp"

namespace railvsi {

DenseMatrix residual_flexibility(const DenseMatrix& F, const DenseMatrix& rows_a, const DenseMatrix& rows_b,
                                 const std::vector<double>& omega_rad_s) {
  Vector inv_w2(static_cast<Eigen::Index>(omega_rad_s.size()));
  for (std::size_t k = 0; k < omega_rad_s.size(); ++k)
    inv_w2[static_cast<Eigen::Index>(k)] = 1.0 / (omega_rad_s[k] * omega_rad_s[k]);
  DenseMatrix R = F;
  R.noalias() -= rows_a.transpose() * inv_w2.asDiagonal() * rows_b;
  return R;
}

DenseMatrix residual_flexibility(const DenseMatrix& F_rail, const DenseMatrix& rail_rows,
                                 const std::vector<double>& omega_rad_s) {
  const DenseMatrix R = residual_flexibility(F_rail, rail_rows, rail_rows, omega_rad_s);
  // Symmetric by construction; the product's round-off is not.
  return (0.5 * (R + R.transpose())).eval();
}

DenseMatrix static_rail_flexibility(const StructureModel& model) {
  // The FE backend's own rail flexibility of K (factors 0, 0, 1): the track
  // substructure or the rails-last factor, as for a time step's K_bar.
  const CholmodOperator K(model, EffectiveMatrixFactors{0.0, 0.0, 1.0}, CholmodOperatorOptions{});
  return K.rail_flexibility();
}

}  // namespace railvsi

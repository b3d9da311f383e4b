#include "integration/modal_recurrence.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace railvsi {

ModalStep make_modal_step(double omega, double zeta, double dt) {
  // z = [q, q', p, p']: z' = M z with p' constant over the step.
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  M(0, 1) = 1.0;
  M(1, 0) = -omega * omega;
  M(1, 1) = -2.0 * zeta * omega;
  M(1, 2) = 1.0;
  M(2, 3) = 1.0;
  const Eigen::Matrix4d E = (M * dt).exp();
  ModalStep s;
  s.omega = omega;
  s.zeta = zeta;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) s.phi[i][j] = E(i, j);
    s.g0[i] = E(i, 2);
    s.g1_per_dt[i] = E(i, 3) / dt;
  }
  return s;
}

}  // namespace railvsi

#include "generators/hex8_element.hpp"

#include <array>
#include <cmath>

namespace railvsi {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
constexpr int kNodal = 24, kInternal = 9, kAll = kNodal + kInternal;
using StrainMatrix = Eigen::Matrix<double, 6, kAll>;

// Strains (xx, yy, zz, xy, yz, zx) from the gradient g of a scalar shape
// function multiplying displacement component c.
void add_gradient(StrainMatrix& B, int column, int c, const std::array<double, 3>& g) {
  B(c, column) = g[c];
  // Engineering shear strains: xy gets u_y + v_x, yz gets v_z + w_y, zx gets w_x + u_z.
  static constexpr int kShear[3][2] = {{3, 5}, {3, 4}, {4, 5}};  // shears component c enters
  static constexpr int kOther[3][2] = {{1, 2}, {0, 2}, {1, 0}};  // the derivative it enters with
  for (int s = 0; s < 2; ++s) B(kShear[c][s], column) = g[kOther[c][s]];
}

Matrix6 isotropic_elasticity(double E, double nu) {
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu = E / (2.0 * (1.0 + nu));
  Matrix6 D = Matrix6::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) {
    D(i, i) += 2.0 * mu;
    D(3 + i, 3 + i) = mu;
  }
  return D;
}

}  // namespace

Matrix24 hex8_box_stiffness(double E_Pa, double poisson, double dx_m, double dy_m, double dz_m) {
  const Matrix6 D = isotropic_elasticity(E_Pa, poisson);
  const std::array<double, 3> scale{2.0 / dx_m, 2.0 / dy_m, 2.0 / dz_m};  // d(xi)/dx
  const double det_J = dx_m * dy_m * dz_m / 8.0;
  const double gauss = 1.0 / std::sqrt(3.0);
  Eigen::Matrix<double, kAll, kAll> K = Eigen::Matrix<double, kAll, kAll>::Zero();
  for (int p = 0; p < 8; ++p) {
    const std::array<double, 3> xi{(p & 1) ? gauss : -gauss, (p & 2) ? gauss : -gauss, (p & 4) ? gauss : -gauss};
    StrainMatrix B = StrainMatrix::Zero();
    for (int n = 0; n < 8; ++n) {
      const std::array<double, 3> corner{(n & 1) ? 1.0 : -1.0, (n & 2) ? 1.0 : -1.0, (n & 4) ? 1.0 : -1.0};
      std::array<double, 3> g{};
      for (int d = 0; d < 3; ++d) {
        double dN = corner[d] / 8.0;
        for (int e = 0; e < 3; ++e)
          if (e != d) dN *= 1.0 + corner[e] * xi[e];
        g[d] = dN * scale[d];
      }
      for (int c = 0; c < 3; ++c) add_gradient(B, 3 * n + c, c, g);
    }
    // Incompatible mode m (1 - xi_m^2) for each component c.
    for (int m = 0; m < 3; ++m) {
      std::array<double, 3> g{};
      g[m] = -2.0 * xi[m] * scale[m];
      for (int c = 0; c < 3; ++c) add_gradient(B, kNodal + 3 * m + c, c, g);
    }
    K += B.transpose() * D * B * det_J;
  }
  const auto Kaa = K.bottomRightCorner<kInternal, kInternal>();
  const auto Kua = K.topRightCorner<kNodal, kInternal>();
  const Eigen::Matrix<double, kInternal, kNodal> X = Kaa.ldlt().solve(Kua.transpose());
  Matrix24 Ke = K.topLeftCorner<kNodal, kNodal>() - Kua * X;
  return 0.5 * (Ke + Ke.transpose());  // exact symmetry for the assembled matrix check
}

}  // namespace railvsi

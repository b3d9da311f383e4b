#pragma once
// 8-node hexahedron for a rectangular box (edges along x, y, z), isotropic
// linear elasticity, 3 DOFs (u, v, w) per node, with Wilson's incompatible
// modes (1 - xi^2, 1 - eta^2, 1 - zeta^2 per displacement component, nine
// internal DOFs condensed out). The plain trilinear element locks in
// bending (parasitic shear); the incompatible modes represent pure bending
// exactly, and on a box they pass the patch test (their derivatives
// integrate to zero over the element). 2x2x2 Gauss integration.
//
// Local node n sits at corner (n & 1, (n >> 1) & 1, (n >> 2) & 1) of the
// box, 0 at the low end and 1 at the high end of x, y, z; DOF 3n + c is
// the displacement of node n along axis c.
#include <Eigen/Dense>

namespace railvsi {

using Matrix24 = Eigen::Matrix<double, 24, 24>;

Matrix24 hex8_box_stiffness(double E_Pa, double poisson, double dx_m, double dy_m, double dz_m);

}  // namespace railvsi

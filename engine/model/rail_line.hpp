#pragma once
// A rail line: the ordered beam elements a wheel can run on. A wheel at x is
// located on one element and the rail top displacement under it is the cubic
// Hermite interpolation of the element's end displacements and rotations.
// DOFs are stored per element so that two simply supported spans meeting at a
// pier can each keep their own end rotation under one x.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace railvsi {

// Hermite row of one wheel on one rail element: rail top = sum weight[k]*u[dof[k]],
// its slope d/dx = sum slope[k]*u[dof[k]] and curvature d2/dx2 likewise
// (rigid contact needs them for the wheel's convective velocity and
// acceleration). Constrained DOFs carry dof = -1 and zero weights.
struct RailContactRow {
  int element = -1;
  std::array<int, 4> dof{-1, -1, -1, -1};
  std::array<double, 4> weight{0.0, 0.0, 0.0, 0.0};
  std::array<double, 4> slope{0.0, 0.0, 0.0, 0.0};
  std::array<double, 4> curvature{0.0, 0.0, 0.0, 0.0};
};

struct RailLine {
  std::string name;
  std::vector<double> x_m;                     // node x, strictly increasing
  std::vector<std::array<int, 4>> element_dofs;  // (v_i, rot_i, v_j, rot_j) per element, -1 fixed

  // The usual case: one vertical and one rotation DOF per node.
  static RailLine from_nodes(std::string name, std::vector<double> x_m, const std::vector<int>& dof_v,
                             const std::vector<int>& dof_rot);

  std::size_t num_elements() const { return element_dofs.size(); }
  double start_m() const { return x_m.front(); }
  double end_m() const { return x_m.back(); }
  bool covers(double x) const { return x >= x_m.front() && x <= x_m.back(); }
  // Empty when x lies outside the modelled track (the wheel is on a rigid path).
  std::optional<RailContactRow> locate(double x) const;
  // The same row with its weights alone (slope and curvature left zero): for
  // callers that read the displacement only (static influence lines), which
  // evaluate it millions of times.
  std::optional<RailContactRow> locate_weights(double x) const;

 private:
  std::optional<RailContactRow> locate(double x, bool derivatives) const;
};

// Cubic Hermite shape functions on an element of length h at xi in [0,1]:
// weights of (v_i, theta_i, v_j, theta_j), theta = dv/dx.
std::array<double, 4> hermite_weights(double xi, double h);
// Their first and second derivatives with respect to x.
std::array<double, 4> hermite_slopes(double xi, double h);
std::array<double, 4> hermite_curvatures(double xi, double h);

}  // namespace railvsi

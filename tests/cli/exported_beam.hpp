#pragma once
// A beam exported the way another program would hand a model to vsi: Matrix
// Market K and M plus the JSON map of its rail line and output point.
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/types.hpp"
#include "generators/beam_element.hpp"

namespace railvsi::test {

struct ExportedBeam {
  DenseMatrix K, M;
  nlohmann::json map;
};

// n_el (even) elements over length_m; `supported`: simply supported, else
// free-free (a mechanism: two rigid-body modes).
inline ExportedBeam exported_beam(int n_el, double length_m, bool supported) {
  const double h = length_m / n_el, EI = 5.0e9, mass = 8000.0;
  std::vector<int> v, rot;
  std::vector<double> x;
  int n = 0;
  for (int i = 0; i <= n_el; ++i) {
    const bool fixed = supported && (i == 0 || i == n_el);
    v.push_back(fixed ? -1 : n++);
    rot.push_back(n++);
    x.push_back(i * h);
  }
  ExportedBeam beam{DenseMatrix::Zero(n, n), DenseMatrix::Zero(n, n), {}};
  for (int e = 0; e < n_el; ++e) {
    const int dofs[4] = {v[e], rot[e], v[e + 1], rot[e + 1]};
    const Matrix4 k = beam_stiffness(EI, h), m = beam_consistent_mass(mass, h);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (dofs[a] >= 0 && dofs[b] >= 0) {
          beam.K(dofs[a], dofs[b]) += k(a, b);
          beam.M(dofs[a], dofs[b]) += m(a, b);
        }
  }
  beam.map = {{"rail_lines", {{{"name", "deck"}, {"x_m", x}, {"dof_v", v}, {"dof_rot", rot}}}},
              {"output_points", {{{"name", "mid"}, {"x_m", length_m / 2}, {"dof", v[n_el / 2]}}}}};
  return beam;
}

// Lower triangle as "symmetric" when asked, else every non-zero as "general".
inline std::string matrix_market(const DenseMatrix& A, bool symmetric) {
  std::string entries;
  int count = 0;
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index i = symmetric ? j : 0; i < A.rows(); ++i)
      if (A(i, j) != 0.0) {
        entries += fmt::format("{} {} {:.17g}\n", i + 1, j + 1, A(i, j));
        ++count;
      }
  return fmt::format("%%MatrixMarket matrix coordinate real {}\n% written by the vsi tests\n{} {} {}\n{}",
                     symmetric ? "symmetric" : "general", A.rows(), A.cols(), count, entries);
}

// A scene running the small scene's train over an imported structure.
inline nlohmann::json imported_scene(nlohmann::json scene) {
  scene["structure"] = {{"import", {{"K", "K.mtx"}, {"M", "M.mtx"}, {"map", "map.json"}}},
                        {"damping", {{"ratio", 0.01}, {"f1_hz", 10.0}, {"f2_hz", 40.0}}}};
  scene.erase("outputs");
  return scene;
}

}  // namespace railvsi::test

#pragma once
// The floor every benchmark reports against: the mean time of one structure
// solve with the cached factor, measured in the same process.
#include <chrono>

#include "solver/structure_operator.hpp"

namespace railvsi::bench {

inline double seconds_per_solve(const StructureOperator& op, int reps) {
  auto ws = op.make_workspace();
  Vector b = Vector::Ones(op.num_dofs()), x;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) {
    (void)op.solve(b, x, *ws);
    b[i % b.size()] += 1e-3 * x[0];  // keep the loop honest
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / reps;
}

}  // namespace railvsi::bench

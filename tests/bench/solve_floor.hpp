#pragma once
// The floor every benchmark reports against: the mean time of one structure
// solve with the cached factor, measured in the same process.
#include <chrono>
#include <ctime>

#include "solver/structure_operator.hpp"

namespace railvsi::bench {

// Process CPU time: on a machine shared with other work, the wall time
// measures the load as much as the code; benchmarks report both.
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

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

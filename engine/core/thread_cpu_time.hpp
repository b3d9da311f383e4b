#pragma once
// The calling thread's CPU time in seconds (what a setup's parts cost;
// other threads' work is not theirs).
#include <ctime>

namespace railvsi {

inline double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace railvsi

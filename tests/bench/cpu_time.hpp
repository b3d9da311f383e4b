#pragma once
// CPU time, for ratios measured in one run on a machine others share: a
// thread's own time does not count the time it waited for a core.
#include <ctime>

namespace railvsi::bench {

inline double cpu_s(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
inline double thread_cpu_s() { return cpu_s(CLOCK_THREAD_CPUTIME_ID); }
inline double process_cpu_s() { return cpu_s(CLOCK_PROCESS_CPUTIME_ID); }

}  // namespace railvsi::bench

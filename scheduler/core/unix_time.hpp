#pragma once
// Wall-clock time as Unix seconds: leases and timestamps in the database,
// comparable between processes (and hosts with synchronized clocks).
#include <chrono>

namespace railvsi::scheduler {

inline double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace railvsi::scheduler

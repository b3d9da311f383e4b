#include "core/huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace railvsi {

void reexec_with_huge_pages(char** argv, bool single_threaded_blas) {
  bool changed = false;
  // OpenBLAS reads its thread count when it is loaded, before main, and its
  // threads then spin waiting for work: unless the variable is set by the
  // caller, set it for the process re-executed.
  if (single_threaded_blas && std::getenv("OPENBLAS_NUM_THREADS") == nullptr) {
    if (setenv("OPENBLAS_NUM_THREADS", "1", 0) != 0) return;
    changed = true;
  }
  constexpr const char* kTunable = "glibc.malloc.hugetlb=1";
  const char* opt_out = std::getenv("RAILVSI_HUGE_PAGES");
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string current = tunables ? tunables : "";
  std::string mode;
  std::getline(std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"), mode);
  const bool want_huge_pages = !(opt_out && std::string(opt_out) == "0") &&
                               current.find("glibc.malloc.hugetlb=") == std::string::npos &&  // set (or refused) already
                               !mode.empty() && mode.find("[never]") == std::string::npos;
  if (want_huge_pages) {
    const std::string value = current.empty() ? kTunable : current + ":" + kTunable;
    if (setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0) changed = true;
  }
  if (changed) execv("/proc/self/exe", argv);
  // exec failed (or nothing to change): run as it is; the variables stay
  // set, so that children do not retry.
}

}  // namespace railvsi

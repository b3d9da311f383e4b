#pragma once
// glibc's malloc gives a freed block of 128 KiB or more straight back to the
// kernel (it was mapped on its own), and trims the heap's free top past
// 128 KiB; it raises those thresholds only after such a block is freed
// ("Memory Allocation Tunables" of the glibc manual, mallopt(3)). A worker
// reuses buffers of a few hundred KiB job after job (a run's accelerations,
// the filter's lanes), so each job faulted their pages in again: on the
// HSLM sweep 13,600 page faults of which 9,800 went away with fixed
// thresholds, and the code filter's share of a job from 49 to 21 us.
#include <cstddef>

namespace railvsi {

// At the start of main (a process-wide setting, not for library code):
// blocks below `bytes` come from the heap, and the heap keeps up to twice
// that free at its top for the next job. Returns false when glibc refused
// a value (the defaults then stay).
bool keep_freed_memory(std::size_t bytes = std::size_t{32} << 20);

}  // namespace railvsi

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

// At the start of main, likewise: every thread allocates from the main
// heap. glibc gives a thread that allocates while another does an arena of
// its own (a fresh 64 MiB mapping), so a worker thread of a process that
// runs one study faulted in every page it used: 1,111 page faults in the
// work of the 1,010-job HSLM sweep, 76 with one heap, and 17 ms of its
// 173 ms of CPU. The workers' time loops do not allocate, so they do not
// wait for each other on its lock. Returns false when glibc refused.
bool one_heap_for_all_threads();

}  // namespace railvsi

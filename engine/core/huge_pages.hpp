#pragma once
// Transparent huge pages for the heap. A seed-scale model churns through
// gigabytes of fresh memory (matrices, their sums, the factor); with 4 KiB
// pages every first touch is a page fault, and on a virtual machine the
// faults took a third of the setup (kernel time in a profile of
// seed_scale_bench). glibc's malloc asks the kernel for huge pages
// (madvise(MADV_HUGEPAGE)) when the tunable glibc.malloc.hugetlb=1 is set
// (glibc >= 2.35, "Memory Allocation Tunables" of the glibc manual), which
// it reads only at process start: so a program that wants it re-executes
// itself once with the tunable added to GLIBC_TUNABLES.
namespace railvsi {

// At the very start of main, before anything is read or written: re-executes
// /proc/self/exe with argv and glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES,
// unless it is there already, RAILVSI_HUGE_PAGES=0 is set, or the kernel has
// transparent huge pages off. With single_threaded_blas, also when
// OPENBLAS_NUM_THREADS is not set, which it then sets to 1: OpenBLAS reads
// it only when it is loaded, before main, and its idle threads spin at
// start (about 0.12 s of CPU in a `vsi run` of 1,010 modal jobs, a third of
// it). Returns when it does not re-execute (or the exec fails: the program
// then runs as it is).
void reexec_with_huge_pages(char** argv, bool single_threaded_blas = false);

}  // namespace railvsi

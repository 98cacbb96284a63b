// The C library's heap, set for a run's output: glibc gives freed memory at
// the top of the heap back to the system (brk) once 128 KiB are free, and
// serves blocks of 128 KiB or more by mmap/munmap. zlib allocates and frees
// about 256 KiB of state for every block VTK compresses, so every VTK step
// file shrank and grew the heap dozens of times, and in a process with
// other threads (OpenMP, CHOLMOD) each shrink flushes the other cores' TLBs
// (an inter-processor interrupt, slow in a virtual machine): a 300-iteration
// run of fish_linkage took 29 s with a step per iteration against 0.7 s
// with none, most of it in the kernel. Keeping up to 256 MiB of freed heap
// and serving blocks of up to 32 MiB from it brought it to 6-10 s.
#pragma once

namespace xshell {

// Sets the heap's trim and mmap thresholds (M_TRIM_THRESHOLD 256 MiB,
// M_MMAP_THRESHOLD 32 MiB) once per process; later calls do nothing.
// Elsewhere than glibc, nothing.
void keep_freed_heap();

}  // namespace xshell

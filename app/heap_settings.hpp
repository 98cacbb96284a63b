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
//
// Page faults are slow here too (a trap into the kernel for every 4 KiB
// first touched): a plain manta_ray relaxation faulted 9,200 times. The
// heap's first 240 MiB are therefore asked to be backed by transparent huge
// pages (madvise MADV_HUGEPAGE; the system's default "madvise" mode serves
// them only so), 2 MiB per fault: 4,000 faults, the run 0.28 -> 0.21 s; the
// manta_ray deployment 26,900 -> 16,500 faults, 1.46 -> 1.35 s, its peak
// memory 88 -> 90 MB; the largest design's relaxation from flat 36,400 ->
// 4,900 faults, 7.1 -> 6.8 s (80 MiB of advice: 36,400, no gain).
#pragma once

namespace xshell {

// Sets the heap's trim and mmap thresholds (M_TRIM_THRESHOLD 256 MiB,
// M_MMAP_THRESHOLD 32 MiB) and advises huge pages for the heap's first
// 240 MiB once per process; later calls do nothing.
// Elsewhere than glibc, nothing.
void keep_freed_heap();

}  // namespace xshell

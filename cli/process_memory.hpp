#pragma once
// How the daylit process asks glibc for memory, set once as main begins: the reflected components
// fill hundreds of MB of rows and matrices, page by page, and on a virtual machine each page's
// first touch costs a few µs.

namespace daylit::cli {

// Runs this program again, once, with glibc's malloc asking for transparent huge pages
// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1), where that is what the kernel waits for (its
// transparent_hugepage/enabled is "madvise": pages of 2 MB only for memory that asks) and the
// user has not said otherwise (the tunable unset, no LD_PRELOAD: an allocator or a tool such as
// valgrind of the user's is left as it is). glibc reads its tunables only as a program starts
// and has no call that sets this one later, hence the second start (about 15 ms), which must come
// before anything else: before MPI starts and before any thread. Where the program cannot be run
// again, it goes on as it is. Measured (paired, whole process, 2 threads): the room sample's
// whole DF at 1 % of its IRC 2.53 → 2.27 s wall (CPU 4.60 → 4.11 s), the office's df with
// every component 14.3 → 13.4 s wall (CPU 27.1 → 25.5 s); the office's peak memory 5 % higher.
void use_transparent_huge_pages(char** argv);

// glibc hands allocations above a threshold to mmap and gives each back to the system when it is
// freed, and raises that threshold only after freeing one: the reflected components allocate
// blocks of 1–30 MB again and again (an annual run's matrices per block of hours, the rows of K),
// so whether each is page-faulted in afresh depended on what had been freed before. Measured on
// the office's 300-sensor annual run with reflections: the hourly part 11.8 s or 20.2 s (6.3 s of
// system time) by that alone. Up to glibc's largest threshold (32 MB on 64-bit) they come from the
// heap, and the heap is not trimmed back while the run lasts.
void keep_freed_memory();

}  // namespace daylit::cli

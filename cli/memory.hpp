// The command's memory set-up (memory.cpp).
#pragma once

#include <memory>

namespace minksum::cli {

// Keep freed memory for reuse and back the heap with transparent huge pages
// where the kernel offers them on request, so that a run touches far fewer
// fresh pages.  Best effort: any call that fails leaves the defaults.
void tune_memory();

// Give each worker thread a malloc arena of its own (up to one per hardware
// thread) instead of tune_memory's single shared one.  For long work whose
// threads allocate constantly (the non-convex sum's exact rationals): on one
// shared arena the threads wait on its lock and two threads ran slower than
// one.  glibc fixes the number of arenas the first time a thread other than
// the main one allocates, so call it before any worker thread has run.
void allow_thread_arenas();

// Route GMP's allocations (every exact number) through per-thread free
// lists of small blocks on top of malloc: an exact sum creates and drops
// millions of numbers of a few hundred bits, and glibc's free costs about a
// hundred instructions each there.  Safe at any point of the run: a block's
// class is its malloc_usable_size, so blocks allocated before (by malloc,
// through GMP's default functions) are reused correctly.
void pool_gmp_memory();

// Leave `data` to the end of the process instead of freeing it: for the
// large structures of a run that are dead before the run ends (a non-convex
// sum's pieces, millions of small blocks), whose freeing would only cost
// time while the output is written (freed by one thread while another
// allocates, they flood malloc's free lists and the writing thread pays for
// their consolidation), as compilers skip freeing at exit.  The memory is
// not used again, so the peak does not grow.  Under AddressSanitizer the
// data is freed at once (its leak check would report it).
void leave_to_exit(std::shared_ptr<void> data);

}  // namespace minksum::cli

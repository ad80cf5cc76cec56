// minksum — independent jobs on a pool of threads (batches of sums).
//
// parallel_for(n, threads, job) calls job(i) once for every i in [0, n), on
// `threads` threads (0: one per hardware thread; never more threads than
// jobs; 1: on the calling thread, no thread started).  A parallel_for called
// from inside a job of another runs on that job's thread (the outer loop
// already keeps the threads busy: no threads times threads), e.g. the
// validation of a large mesh inside a batch of sums.  The jobs are handed
// out one at a time in index order, so a long job does not hold up the
// others behind a fixed share.  Every computation of minksum is independent
// of the others (no global state), so jobs may compute sums, hulls and loads
// concurrently; they must not write shared data without their own
// synchronisation (writing slot i of a pre-sized vector is fine).
//
// The threads are a pool started on first use and reused by later loops
// (kernel/parallel.cpp), so a loop of a few milliseconds does not pay for
// starting threads; two loops running at once from different threads of an
// application each get their threads.
//
// An exception thrown by a job is not lost: the first one (in index order)
// is rethrown by parallel_for once every thread has stopped; after a job has
// thrown, no job with a larger index starts.  Callers that want one outcome
// per job catch inside the job (minksum batch and the Python binding do).
#pragma once

#include <cstddef>
#include <functional>

namespace minksum {

// The number of hardware threads (at least 1), read once.
unsigned hardware_threads();

// The number of threads parallel_for runs for `threads` (0: hardware) and n jobs.
unsigned parallel_threads(unsigned threads, std::size_t n);

void parallel_for(std::size_t n, unsigned threads, const std::function<void(std::size_t)>& job);

// minksum's own loops over one mesh or one text (validating a mesh, the
// certificate of rounded coordinates, reading the faces of an OFF file,
// formatting lines of text) run on threads from this many items (facets,
// faces, lines) on, and on the calling thread below.  A loop below it is a
// few milliseconds or less; with two hardware threads that share a core (a
// virtual machine's vCPUs, SMT siblings) waking the second and waiting for
// its share costs about what it saves on the median and much more on a bad
// run: measured on a 2-vCPU machine, `minksum sum` of a cube and a
// 20 480-facet sphere, file to file, took 16.7 ms on one thread against
// 21.6 ms on two (medians of 40 interleaved runs; quartiles 16.5-17.1 ms
// against 17.3-26.8 ms; bench/e2e.py --baseline, docs/data-model.md).
// The default is kParallelItems; set_parallel_items changes it for the
// whole process (tests use small values to run the threaded paths on small
// inputs; 1 puts every such loop on threads).
inline constexpr std::size_t kParallelItems = std::size_t(1) << 17;
std::size_t parallel_items();
void set_parallel_items(std::size_t items);

}  // namespace minksum

// Memory set-up for the command line.
//
// A `minksum sum` from file to file spends much of its time in first-touch
// page faults, not in arithmetic: on virtual machines one fault costs
// several microseconds, and a run on 10 000-vertex operands touches a few
// thousand fresh 4 KiB pages (vectors grown, freed and allocated again).
// Four malloc settings (mallopt) and one madvise cut that:
//   * large blocks stay in the heap instead of their own mappings, and freed
//     memory is kept rather than returned, so it is reused without faulting
//     again (M_MMAP_THRESHOLD at its maximum, M_TRIM_THRESHOLD);
//   * the heap grows by 64 MiB at a time (M_TOP_PAD), and that region is
//     marked MADV_HUGEPAGE, so a fault maps 2 MiB at once where the kernel
//     has transparent huge pages in "madvise" (or "always") mode;
//   * one arena for all threads (M_ARENA_MAX): the library's worker threads
//     (validation in blocks, files read and formatted in parallel) then
//     allocate from that same huge-page heap instead of fresh per-thread
//     arenas, which would fault 4 KiB at a time.
// This is what glibc's own tunables glibc.malloc.hugetlb=1 and
// glibc.malloc.{mmap,trim}_threshold do, set from inside the program.  The
// library does not do it: an application embedding it keeps its own policy.
#include "memory.hpp"

#include <minksum/parallel.hpp>

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace minksum::cli {

namespace {
void* volatile heap_filler = nullptr;  // see tune_memory
}  // namespace

void tune_memory() {
  constexpr std::size_t kPad = std::size_t(64) << 20;
  constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // the largest value glibc accepts on 64-bit
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, int(kPad));
  // Grow the heap now (a block below the mmap threshold extends it by the
  // block plus the pad), then advise the whole grown region.
  void* first = std::malloc(std::size_t(16) << 20);
  if (!first) return;
  const auto lo = (reinterpret_cast<std::uintptr_t>(first) + kHuge - 1) & ~(kHuge - 1);
  const auto hi = reinterpret_cast<std::uintptr_t>(sbrk(0)) & ~(kHuge - 1);
  if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
  std::free(first);
  // The heap from where `first` started up to lo (up to 2 MiB) is not in
  // the advised region, and it is where the next blocks would go: the first
  // file read (a megabyte of text) would fault there 4 KiB at a time (about
  // 3 ms for 1 MB here, against 0.2 ms for a huge page).  A block that is
  // never used and never freed takes that stretch; it costs address space,
  // not memory (its pages are never touched).
  if (hi > lo) heap_filler = std::malloc(lo - reinterpret_cast<std::uintptr_t>(first));
}

void allow_thread_arenas() { mallopt(M_ARENA_MAX, int(std::max(2u, hardware_threads()))); }

}  // namespace minksum::cli

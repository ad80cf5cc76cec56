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

#include <gmp.h>
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

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

// The free lists of pool_gmp_memory: block class c holds blocks whose
// malloc_usable_size is at least c granules (and less than c + 1), so a
// request of up to c granules may take one; a new block for class c is
// malloc(c granules), whose usable size glibc makes c granules plus 8 bytes.
// At most kKeep blocks per class stay on a thread's list; the rest go back
// to malloc.  The lists die with their thread (blocks back to malloc); a
// number freed on a thread after that goes to free() directly.
namespace {
constexpr std::size_t kGranule = 16;
constexpr std::size_t kClasses = 65;  // blocks of up to 1 KiB
constexpr unsigned kKeep = 1024;

struct FreeBlock {
  FreeBlock* next;
};

struct ThreadLists {
  FreeBlock* head[kClasses] = {};
  unsigned count[kClasses] = {};
  ~ThreadLists();
};

thread_local bool t_lists_gone = false;  // trivially destructible: readable to the thread's end
thread_local ThreadLists t_lists;

ThreadLists::~ThreadLists() {
  for (std::size_t c = 0; c < kClasses; ++c)
    while (FreeBlock* b = head[c]) {
      head[c] = b->next;
      std::free(b);
    }
  t_lists_gone = true;
}

void* pool_allocate(std::size_t n) {
  const std::size_t c = (n + kGranule - 1) / kGranule;
  if (c < kClasses && !t_lists_gone) {
    ThreadLists& l = t_lists;
    if (FreeBlock* b = l.head[c]) {
      l.head[c] = b->next;
      --l.count[c];
      return b;
    }
    if (void* p = std::malloc(std::max<std::size_t>(c, 1) * kGranule)) return p;
  } else if (void* p = std::malloc(n)) {
    return p;
  }
  // GMP's own default functions abort on failure as well; the command's
  // handlers report std::bad_alloc from C++ allocations, but GMP cannot
  // unwind through C, so abort as GMP does.
  std::fputs("minksum: out of memory\n", stderr);
  std::abort();
}

void pool_free(void* p, std::size_t) {
  if (!p) return;
  const std::size_t c = malloc_usable_size(p) / kGranule;
  if (c < kClasses && !t_lists_gone) {
    ThreadLists& l = t_lists;
    if (l.count[c] < kKeep) {
      auto* b = static_cast<FreeBlock*>(p);
      b->next = l.head[c];
      l.head[c] = b;
      ++l.count[c];
      return;
    }
  }
  std::free(p);
}

void* pool_reallocate(void* p, std::size_t old_size, std::size_t n) {
  if (!p) return pool_allocate(n);
  if (n <= malloc_usable_size(p)) return p;
  void* q = pool_allocate(n);
  std::memcpy(q, p, std::min(old_size, n));
  pool_free(p, old_size);
  return q;
}
}  // namespace

#if defined(__SANITIZE_ADDRESS__)
#define MINKSUM_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MINKSUM_ASAN 1
#endif
#endif

// Under AddressSanitizer GMP keeps malloc and free, so that a number used
// after it is freed is still caught (a recycled block would hide it).
void pool_gmp_memory() {
#ifndef MINKSUM_ASAN
  mp_set_memory_functions(pool_allocate, pool_reallocate, pool_free);
#endif
}

void leave_to_exit(std::shared_ptr<void> data) {
#ifdef MINKSUM_ASAN
  data.reset();
#else
  static std::vector<std::shared_ptr<void>>* const kept = new std::vector<std::shared_ptr<void>>;  // never freed
  kept->push_back(std::move(data));
#endif
}

void allow_thread_arenas() { mallopt(M_ARENA_MAX, int(std::max(2u, hardware_threads()))); }

}  // namespace minksum::cli

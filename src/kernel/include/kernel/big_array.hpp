// Internal: arrays of a few words per vertex, edge or corner of a large mesh,
// on transparent huge pages where the system offers them.
//
// Validating a million-vertex mesh fills some twenty arrays of 4 to 48 MB.
// On 4 KiB pages each array costs one page fault per 4 KiB when first
// written (about 130 000 faults for such a mesh, a fifth of the validation's
// time on a virtual machine); a Linux kernel whose transparent huge pages
// are in "madvise" mode (the usual default) maps 2 MiB pages for memory
// advised with MADV_HUGEPAGE, 512 times fewer faults.  The advice changes
// no value, only how the memory is mapped; elsewhere it is a no-op.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace minksum {

// Reserve room for n elements in v and, when v's buffer is new and large,
// advise the kernel to back it with huge pages before it is first written.
template <class T>
void reserve_big(std::vector<T>& v, std::size_t n) {
  v.reserve(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t begin = (first + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (first + v.capacity() * sizeof(T)) & ~(kHuge - 1);
  if (end >= begin + 2 * kHuge) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

// n copies of `value`, reserved by reserve_big.
template <class T>
std::vector<T> big_array(std::size_t n, const T& value = T()) {
  std::vector<T> v;
  reserve_big(v, n);
  v.assign(n, value);
  return v;
}

// Free v's memory now.  (`v = {}` does not: for a std::vector it picks the
// initializer_list assignment, which empties v but keeps its capacity.)
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

}  // namespace minksum

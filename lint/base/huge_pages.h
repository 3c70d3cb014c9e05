// Large buffers: ask Linux to back them with 2 MB pages. A 100 MB input otherwise takes ~100,000 page faults
// (each a trap and a 4 KB clear) across its text, line index and records; with huge pages it takes a few hundred.
// Only touched pages count, so a generous reservation still costs nothing. Elsewhere this does nothing.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace rrflint {

/// Advises huge pages for the 2 MB-aligned part of [p, p + bytes), when that is at least 4 MB.
inline void advise_huge_pages(const void* p, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr uintptr_t kHuge = uintptr_t{2} << 20;
  if (bytes < 2 * kHuge) return;
  const auto begin = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const auto end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

/// Maps `size` (> 0) bytes of the open file `fd` read-only, or returns nullptr (then read it instead).
inline const char* map_bytes(int fd, size_t size) {
#if defined(__linux__)
  void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  if (p == MAP_FAILED) return nullptr;
  ::madvise(p, size, MADV_SEQUENTIAL);
  return static_cast<const char*>(p);
#else
  (void)fd;
  (void)size;
  return nullptr;
#endif
}

/// Undoes map_bytes.
inline void unmap_bytes(const char* p, size_t size) {
#if defined(__linux__)
  ::munmap(const_cast<char*>(p), size);
#else
  (void)p;
  (void)size;
#endif
}

/// Reserves `n` elements of `v` and advises huge pages for them.
template <class Vector>
void reserve_huge(Vector& v, size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(*v.data()));
}

}  // namespace rrflint

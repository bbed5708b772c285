// Large arrays of the BVH build on transparent huge pages. A 1M-primitive build touches about
// 150 MB of fresh memory; with 4 KiB pages the kernel's page faults alone took a quarter of
// the build time (docs/ray-tracing.md, "Build times"). Asking for transparent huge pages
// (Linux, madvise mode) cuts their number 512-fold. Elsewhere these are no-ops.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace bounce::rt {

// Advises the whole 2 MiB pages inside [data, data + bytes); call it before the first write.
inline void adviseHugePages(void* data, size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
  uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kHugePage - 1) & ~(kHugePage - 1);
  uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// Reserves room for `count` elements of an empty vector and advises it as above.
template <typename T>
void reserveLarge(std::vector<T>& v, size_t count) {
  v.reserve(count);
  adviseHugePages(v.data(), count * sizeof(T));
}

// resize() of an empty vector to `count` elements, on advised memory.
template <typename T>
void resizeLarge(std::vector<T>& v, size_t count) {
  reserveLarge(v, count);
  v.resize(count);
}

}  // namespace bounce::rt

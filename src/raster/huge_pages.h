// shadowvol raster: per-pixel buffers in huge pages where the system offers them.
//
// A 1920 x 1080 frame's buffers (depth, counts, ids, and the frame's ids, masks and image) are
// some 50 MB; first touched in 4 KiB pages that is about 15,000 page faults, most of a cold
// frame's extra cost. Asking for transparent huge pages (Linux's madvise(MADV_HUGEPAGE), which
// systems set to "madvise" honour) makes it a few dozen. A hint only: where it is not honoured,
// or not on Linux, nothing changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace shadowvol::raster {

// Gives `buffer` room for `n` elements (reserve) and asks for huge pages over the part of it
// that whole 2 MiB pages cover, before its first touch; call it before resize or assign.
template <class T>
void reserve_in_huge_pages(std::vector<T>& buffer, std::size_t n) {
  if (buffer.capacity() >= n) return;
  buffer.reserve(n);
#ifdef __linux__
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(buffer.data());
  const std::uintptr_t end = begin + buffer.capacity() * sizeof(T);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = end & ~(kHugePage - 1);
  if (first < last) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

}  // namespace shadowvol::raster

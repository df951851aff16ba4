// A backend's large host arrays (the table, per-record keys and placements) are touched at random, a few
// words per record: on 4 KiB pages that costs a page fault per 4 KiB when they are first written and a TLB
// miss on almost every access. Sizing them through this asks Linux for transparent huge pages first, where its
// setting is `madvise`; elsewhere it is a plain resize. Contents and results do not change.
#ifndef HPSF_CORE_HUGE_PAGES_H
#define HPSF_CORE_HUGE_PAGES_H

#include <cstddef>
#include <vector>

namespace hpsf {

// Advises huge pages for the whole 2 MiB pages inside [data, data + bytes); a no-op for small ranges.
void AdviseHugePages(void* data, std::size_t bytes);

// v.resize(n) with value-initialised elements, the storage advised before its first write.
template <typename T>
void ResizeOnHugePages(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) {
    std::vector<T> fresh;
    fresh.reserve(n);  // allocates without touching the pages
    AdviseHugePages(fresh.data(), n * sizeof(T));
    fresh.assign(v.begin(), v.end());
    v = std::move(fresh);
  }
  v.resize(n);
}

}  // namespace hpsf

#endif  // HPSF_CORE_HUGE_PAGES_H

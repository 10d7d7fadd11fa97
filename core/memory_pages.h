#pragma once
// Fresh memory's pages mapped ahead of writing, for arrays of megabytes that are filled once.

#include <cstddef>
#include <vector>

namespace tessera {

/// Maps the whole pages inside [data, data + bytes) in one system call (madvise with
/// MADV_POPULATE_WRITE, Linux 5.14), where writing them one after another takes a page fault
/// each 4 KiB: the faults of a glb's meshes were a fifth of its import, more on virtual
/// machines, where a fault is costlier (docs/performance.md, "Loading speed"). Memory use is the
/// same: these are pages the caller is about to write. Does nothing for ranges under 16 KiB,
/// and where the kernel lacks the call (a hint: then the pages fault in as they are written).
/// Returns whether the pages were mapped.
bool populate_pages(void* data, size_t bytes);

/// `v` with capacity for `n` elements, its pages mapped (populate_pages).
template <typename T>
void reserve_populated(std::vector<T>& v, size_t n) {
  v.reserve(n);
  populate_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace tessera

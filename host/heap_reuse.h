#pragma once
// Repeated CPU reference frames on the same pages: glibc's malloc tuned so that memory a frame
// frees is kept for the next (mallopt(3)).

#include <malloc.h>

namespace tessera {

/// Makes glibc's malloc keep freed memory for reuse, for a process about to render reference
/// frames one after another (`render --device reference --repeat`, `bench --backends
/// reference`). Each frame allocates and frees tens of MB (images, texture levels). By default
/// glibc maps blocks above a threshold that it raises as such blocks are freed, and returns
/// the heap's free top to the system, so the second frame, and every frame when the one before
/// is freed first, takes fresh pages: 13,500 page faults a frame on `textured` at 512x512,
/// which made its second frame 3 to 10 times as slow as the ones after it on the 2-core VM.
/// With a fixed threshold of 256 MiB and the heap's top kept up to 512 MiB, a frame freed
/// before the next one leaves its pages to it. Process-wide; the memory held is at most what
/// one frame used.
inline void keep_freed_memory_for_reuse() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

}  // namespace tessera

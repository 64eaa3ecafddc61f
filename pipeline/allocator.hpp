// The process's allocator policy for a simulator that allocates and frees buffers of
// megabytes many times a frame (copies to textures, pixel rectangles, texel caches).
#pragma once

namespace passim {

// glibc maps blocks above a (dynamic) threshold with mmap and gives them back on free, and
// trims the top of the heap; every later allocation of such a size then faults in and zeroes
// fresh pages — measured at a fifth of a fast-pcf frame's time (docs/performance.md). This
// keeps blocks up to 32 MB in the heap and the heap untrimmed below 512 MB, so freed buffers
// are reused. It changes no result and no heap peak (live bytes), only what the process
// keeps mapped. Called by the passim and passim_bench programs; a library user may call it.
void keep_large_blocks_in_the_heap();

}  // namespace passim

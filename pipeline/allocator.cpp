#include "pipeline/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc systems (tested below)

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace passim {

void keep_large_blocks_in_the_heap() {
#if defined(__GLIBC__)
  // 32 MB is glibc's largest mmap threshold on 64-bit systems (DEFAULT_MMAP_THRESHOLD_MAX).
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
  mallopt(M_TOP_PAD, 64 * 1024 * 1024);  // and grow it 64 MB at a time
#endif
}

}  // namespace passim

#include "core/util/heap_trim.h"

#include <cstdlib>  // defines __GLIBC__ with the GNU C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// A sanitizer replaces malloc: glibc's arenas then hold nothing of ours to trim.
#if defined(__SANITIZE_ADDRESS__)
#define ANIMORPH_OWN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ANIMORPH_OWN_ALLOCATOR 1
#endif
#endif

namespace animorph {

bool heapTrimSupported() {
#if defined(__GLIBC__) && !defined(ANIMORPH_OWN_ALLOCATOR)
  return true;
#else
  return false;
#endif
}

bool trimFreedHeap() {
#if defined(__GLIBC__) && !defined(ANIMORPH_OWN_ALLOCATOR)
  return malloc_trim(0) != 0;
#else
  return false;
#endif
}

}  // namespace animorph

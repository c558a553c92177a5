#pragma once
// Giving freed heap memory back to the operating system. glibc's malloc keeps what a thread frees
// in that thread's arena (one per allocating thread, up to 8 per core) for reuse: a process whose
// worker threads allocate large short-lived working sets (the preview polygonisers: about 25 MiB
// for a one-sphere BlobTree at 128^3) keeps them in its resident memory long after they are freed,
// until something trims the heap.
namespace animorph {

// True where trimFreedHeap can return memory: glibc's own malloc (not a sanitizer's allocator).
bool heapTrimSupported();

// Returns the freed pages of every malloc arena to the system (glibc's malloc_trim(0)); true
// when some memory was returned. Thread-safe: it takes each arena's lock in turn, so call it
// once a burst of work is over, not inside one. Does nothing (false) where unsupported.
bool trimFreedHeap();

}  // namespace animorph

#pragma once
// A haptic loop's heap, resident before its first tick. Memory a tick takes
// for the first time costs a page fault per 4 KB page, and glibc's defaults
// add more: a large block (over 128 KB at first; glibc raises the threshold
// up to 32 MB as such blocks are freed) gets its own mapping, unmapped when
// freed and faulted in again when next taken, and the heap's free top goes
// back to the system. On the build machine a fault costs 10 to 20 us: the
// B-spline tool's first stroke on a 64 x 64 panel took 150 faults, up to 40
// in one tick.

#include <cstddef>

namespace argil {

/// Whether keep_heap_resident can work in this build: glibc's allocator, not
/// a sanitizer's (which replaces malloc and ignores glibc's settings).
bool resident_heap_supported();

/// Makes this process's heap keep what it frees (large blocks come from the
/// heap, and its top is never trimmed), then takes `bytes` from the calling
/// thread's heap, writes every page and frees them: the ticks' allocations
/// reuse those pages instead of faulting in fresh ones.
///
/// Process-wide and for the process's life: freed memory is not returned to
/// the system. Call it from the thread that runs the ticks: glibc gives other
/// threads heaps of their own, of 64 MB each, and unmaps one that empties, so
/// there keep `bytes` under 60 MB. False, changing nothing, where
/// resident_heap_supported() is false; an allocator preloaded in glibc's
/// place (jemalloc, tcmalloc) may take the settings and ignore them. `bytes`
/// 0 only makes the settings.
bool keep_heap_resident(std::size_t bytes);

/// What a haptic loop keeps resident (`argil sculpt`, the benchmarks): a
/// stroke on a 64 x 64 panel takes under 2 MB once its world is made; the
/// rest is room for larger scenes. On the main thread, whose heap has no
/// size limit.
inline constexpr std::size_t kHapticHeapReserve = std::size_t{64} << 20;

}  // namespace argil

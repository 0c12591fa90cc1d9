#pragma once
// A haptic loop's heap, resident before its first tick. Memory a tick takes
// for the first time costs a page fault per 4 KB page, and glibc's defaults
// add more: a block over 128 KB gets its own mapping, unmapped when freed and
// faulted in again when next taken, and the heap's free top goes back to the
// system. On the build machine a fault costs 10 to 20 us: the B-spline tool's
// first stroke on a 64 x 64 panel took 150 faults, up to 40 in one tick.

#include <cstddef>

namespace argil {

/// Makes this process's heap keep what it frees (large blocks come from the
/// heap, and its top is never trimmed), then takes `bytes` from the calling
/// thread's heap, writes every page and frees them: the ticks' allocations
/// reuse those pages instead of faulting in fresh ones.
///
/// Process-wide and for the process's life: freed memory is not returned to
/// the system. Call it from the thread that runs the ticks (glibc gives other
/// threads heaps of their own). False, changing nothing, where the allocator
/// is not glibc's (another C library, or a sanitizer's allocator).
bool keep_heap_resident(std::size_t bytes);

}  // namespace argil

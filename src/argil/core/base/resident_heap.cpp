#include "argil/core/base/resident_heap.hpp"

#include <cstdlib>
#include <vector>

// glibc's allocator, unless a sanitizer's replaces it (GCC names those with
// __SANITIZE_*__, clang with __has_feature).
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) && \
    !defined(__SANITIZE_HWADDRESS__)
#if defined(__has_feature)
#if !__has_feature(address_sanitizer) && !__has_feature(hwaddress_sanitizer) && \
    !__has_feature(memory_sanitizer) && !__has_feature(thread_sanitizer)
#define ARGIL_RESIDENT_HEAP 1
#endif
#else
#define ARGIL_RESIDENT_HEAP 1
#endif
#endif

#ifdef ARGIL_RESIDENT_HEAP
#include <malloc.h>
#include <unistd.h>
#endif

namespace argil {

bool resident_heap_supported() {
#ifdef ARGIL_RESIDENT_HEAP
  return true;
#else
  return false;
#endif
}

bool keep_heap_resident(std::size_t bytes) {
#ifdef ARGIL_RESIDENT_HEAP
  // No separate mappings (so no unmapping on free), and no trimming (-1 is
  // the largest threshold: the heap's free top stays mapped).
  if (mallopt(M_MMAP_MAX, 0) != 1 || mallopt(M_TRIM_THRESHOLD, -1) != 1) return false;
  // Pieces of 1 MB rather than one block: a thread's heap holds at most
  // 64 MB in one piece.
  constexpr std::size_t kPiece = std::size_t{1} << 20;
  const long page_size = sysconf(_SC_PAGESIZE);
  const std::size_t page = page_size > 0 ? static_cast<std::size_t>(page_size) : 4096;
  std::vector<void*> pieces;
  pieces.reserve(bytes / kPiece + 1);
  for (std::size_t taken = 0; taken < bytes; taken += kPiece) {
    void* p = std::malloc(kPiece);
    if (p == nullptr) break;  // less memory than asked: keep what was had
    // A write to each page maps it (a read would map the shared zero page).
    // Volatile: a plain memset before free() is a dead store the compiler drops.
    auto* bytes_of = static_cast<volatile unsigned char*>(p);
    for (std::size_t at = 0; at < kPiece; at += page) bytes_of[at] = 0;
    pieces.push_back(p);
  }
  // They merge into the heap's free top, which is never trimmed now.
  for (void* p : pieces) std::free(p);
  return true;
#else
  (void)bytes;
  return false;
#endif
}

}  // namespace argil

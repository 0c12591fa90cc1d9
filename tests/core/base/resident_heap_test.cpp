// keep_heap_resident: after it, memory taken and written up to the reserve
// faults in no fresh pages, in small blocks and in blocks over glibc's
// largest mapping threshold (32 MB), and memory freed stays mapped for the
// next use.
// (Page faults counted by getrusage for this thread.)
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <cstddef>
#include <cstring>
#include <memory>
#include <vector>

#include "argil/core/base/resident_heap.hpp"

namespace {

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_THREAD, &u);
  return u.ru_minflt;
}

/// Takes `total` bytes in blocks of `block`, writes them, frees them; the
/// page faults that took.
long faults_to_use(std::size_t total, std::size_t block) {
  std::vector<std::unique_ptr<char[]>> blocks;
  blocks.reserve(total / block + 1);
  const long before = minor_faults();
  for (std::size_t taken = 0; taken < total; taken += block) {
    blocks.push_back(std::make_unique_for_overwrite<char[]>(block));
    std::memset(blocks.back().get(), 1, block);
  }
  blocks.clear();
  return minor_faults() - before;
}

constexpr std::size_t kMiB = std::size_t{1} << 20;

TEST_CASE("a resident heap serves memory without page faults", "[resident_heap]") {
  if (!argil::resident_heap_supported()) {
    // A sanitizer's allocator ignores glibc's settings: refused, nothing changed.
    CHECK_FALSE(argil::keep_heap_resident(80 * kMiB));
    return;
  }
  // First the measure's own check: under glibc's defaults a block over 32 MB
  // (the most its mapping threshold rises to, whatever ran before) gets a
  // mapping of its own, unmapped when freed, so each use faults its pages in.
  constexpr std::size_t kLarge = 36 * kMiB;
  const long without = faults_to_use(2 * kLarge, kLarge);
  CHECK(without >= static_cast<long>(2 * kLarge / 4096) - 64);

  REQUIRE(argil::keep_heap_resident(80 * kMiB));
  // A few faults of the vector's own growth and the stack are allowed; one
  // fresh megabyte would be 256.
  constexpr long kAllowed = 16;
  CHECK(faults_to_use(2 * kLarge, kLarge) <= kAllowed);  // no mapping of its own
  CHECK(faults_to_use(8 * kMiB, 4096) <= kAllowed);      // many small blocks
  // Used and freed twice over: what was freed stayed mapped.
  CHECK(faults_to_use(2 * kLarge, kLarge) <= kAllowed);
  CHECK(faults_to_use(24 * kMiB, kMiB) <= kAllowed);
}

}  // namespace

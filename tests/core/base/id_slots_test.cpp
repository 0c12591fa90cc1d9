// IdSlots: an id maps to what was set for it since the last clear, -1 before;
// clear forgets every id however large, and ids set after it start clean; the
// table grows with the ids one query sets (against a brute-force map); and
// after 2^32 clears the generation wraps without bringing old ids back.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <random>

#include "argil/core/base/detail/id_slots.hpp"

namespace {

using argil::IdSlots;

TEST_CASE("id slots hold what was set since the last clear", "[id_slots]") {
  IdSlots slots;
  CHECK(slots.find(0) == -1);
  CHECK(slots.find(1000000) == -1);  // nothing stored yet
  slots.set(3, 7);
  slots.set(100000, 0);  // a page of its own, far from the first
  slots.set(3, 9);       // set again: the last value counts
  CHECK(slots.find(3) == 9);
  CHECK(slots.find(100000) == 0);
  CHECK(slots.find(2) == -1);
  CHECK(slots.find(4) == -1);
  CHECK(slots.find(99999) == -1);

  slots.clear();
  CHECK(slots.find(3) == -1);
  CHECK(slots.find(100000) == -1);
  slots.set(4, 1);
  CHECK(slots.find(4) == 1);
  CHECK(slots.find(3) == -1);  // still forgotten: its old stamp is not the new one
}

TEST_CASE("id slots forget every id over many clears", "[id_slots]") {
  IdSlots slots;
  for (int query = 0; query < 1000; ++query) {
    const auto id = static_cast<std::size_t>(query % 37);
    CHECK(slots.find(id) == -1);
    CHECK(slots.find(id + 1) == -1);
    slots.set(id, query);
    slots.set(id + 1, -query);
    CHECK(slots.find(id) == query);
    CHECK(slots.find(id + 1) == -query);
    slots.clear();
  }
}

TEST_CASE("id slots agree with a map over pages, shared low bits and clears", "[id_slots]") {
  IdSlots slots;
  std::mt19937_64 rng(7);
  for (int query = 0; query < 40; ++query) {
    std::map<std::size_t, int> truth;
    // From a handful of ids to thousands: pages are added inside a query
    // and keep what was set before.
    const int count = query % 4 == 0 ? 5000 : 1 + static_cast<int>(rng() % 300);
    for (int k = 0; k < count; ++k) {
      // Dense ids (a hierarchy's nodes), ids that share low bits (one slot
      // of many pages), and ids spread over a million.
      const std::size_t id = k % 3 == 0   ? rng() % 2000
                             : k % 3 == 1 ? (rng() % 64) << 14
                                          : rng() % 1000000;
      const int value = static_cast<int>(rng() % 1000);
      slots.set(id, value);
      truth[id] = value;
    }
    for (const auto& [id, value] : truth) REQUIRE(slots.find(id) == value);
    for (int k = 0; k < 200; ++k) {
      const std::size_t id = rng() % 4000;
      const auto it = truth.find(id);
      CHECK(slots.find(id) == (it == truth.end() ? -1 : it->second));
    }
    if (query == 20) {
      slots.release();
    } else {
      slots.clear();
    }
    for (const auto& [id, value] : truth) REQUIRE(slots.find(id) == -1);
  }
}

TEST_CASE("id slots forget old ids when their generation wraps", "[id_slots]") {
  // A slot stores the generation that wrote it: 2^32 clears later the
  // generation counter comes back to that value, and without the wrap's
  // reset the old value would be found again. (About a second of clears.)
  IdSlots slots;
  slots.set(5, 42);  // generation 1
  slots.clear();
  slots.set(7, 1);  // generation 2
  for (std::uint64_t k = 0; k < (std::uint64_t{1} << 32) - 1; ++k) slots.clear();
  CHECK(slots.find(5) == -1);  // a plain counter would be back at 1 here
  CHECK(slots.find(7) == -1);
  slots.set(5, 3);
  CHECK(slots.find(5) == 3);
  slots.clear();
  CHECK(slots.find(5) == -1);
}

}  // namespace

// ChunkedVector: growth never moves an element, truncation frees the chunks
// past the kept ones, clearing keeps them all for reuse, copies are deep, and
// every element added is destroyed exactly once (chunks are raw storage).
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "argil/core/base/chunked_vector.hpp"

namespace {

using argil::ChunkedVector;

TEST_CASE("a chunked vector keeps its elements in place as it grows", "[chunked_vector]") {
  ChunkedVector<std::string, 4> v;
  CHECK(v.empty());
  std::vector<const std::string*> addresses;
  for (int i = 0; i < 37; ++i) {
    v.push_back(std::string(40, static_cast<char>('a' + i % 26)) + std::to_string(i));
    addresses.push_back(&v[static_cast<std::size_t>(i)]);
  }
  REQUIRE(v.size() == 37);
  for (std::size_t i = 0; i < v.size(); ++i) {
    CHECK(&v[i] == addresses[i]);  // not moved by any later push_back
    CHECK(v[i].substr(40) == std::to_string(i));
  }
}

TEST_CASE("truncating a chunked vector keeps the first elements and resets the rest",
          "[chunked_vector]") {
  ChunkedVector<std::string, 4> v;
  for (int i = 0; i < 11; ++i) v.push_back(std::to_string(i));
  const std::string* kept = &v[5];
  v.truncate(6);
  REQUIRE(v.size() == 6);
  CHECK(&v[5] == kept);
  CHECK(v[5] == "5");
  // The kept chunk's later slots were reset: new elements start clean.
  v.push_back("x");
  CHECK(v[6] == "x");
  v.truncate(0);
  CHECK(v.empty());
  v.push_back("y");
  CHECK(v[0] == "y");
}

TEST_CASE("a cleared chunked vector reuses its chunks", "[chunked_vector]") {
  ChunkedVector<std::string, 4> v;
  for (int i = 0; i < 9; ++i) v.push_back(std::to_string(i));
  const std::string* first = &v[0];
  const std::string* last = &v[8];
  v.clear();
  CHECK(v.empty());
  for (int i = 0; i < 9; ++i) v.push_back("again " + std::to_string(i));
  REQUIRE(v.size() == 9);
  CHECK(&v[0] == first);  // the same storage: nothing allocated
  CHECK(&v[8] == last);
  CHECK(v[8] == "again 8");
  v.push_back("past the old size");  // a new chunk
  CHECK(v[9] == "past the old size");
}

TEST_CASE("a copied chunked vector is independent of the original", "[chunked_vector]") {
  ChunkedVector<int, 3> a;
  for (int i = 0; i < 8; ++i) a.push_back(i * i);
  ChunkedVector<int, 3> b = a;
  b[2] = -1;
  b.push_back(100);
  CHECK(a[2] == 4);
  CHECK(a.size() == 8);
  REQUIRE(b.size() == 9);
  CHECK(b[8] == 100);
  ChunkedVector<int, 3> c;
  c = b;
  CHECK(c[2] == -1);
  CHECK(&c[0] != &b[0]);
}

TEST_CASE("a chunked vector destroys each element it holds exactly once", "[chunked_vector]") {
  // A shared_ptr's use count tells how many copies of it are alive.
  const auto token = std::make_shared<int>(7);
  {
    ChunkedVector<std::shared_ptr<int>, 4> v;
    for (int i = 0; i < 10; ++i) v.push_back(token);
    CHECK(token.use_count() == 11);
    v.truncate(3);  // within a chunk and across chunks
    CHECK(token.use_count() == 4);
    {
      ChunkedVector<std::shared_ptr<int>, 4> cleared = v;
      cleared.push_back(token);
      CHECK(token.use_count() == 8);
      cleared.clear();
      CHECK(token.use_count() == 4);
      cleared.push_back(token);
      CHECK(token.use_count() == 5);
    }
    CHECK(token.use_count() == 4);
    ChunkedVector<std::shared_ptr<int>, 4> copy = v;
    CHECK(token.use_count() == 7);
    ChunkedVector<std::shared_ptr<int>, 4> moved = std::move(copy);
    CHECK(token.use_count() == 7);
    CHECK(moved.size() == 3);
    moved = v;  // copy-assigned over its own elements
    CHECK(token.use_count() == 7);
    v = std::move(moved);
    CHECK(token.use_count() == 4);
  }
  CHECK(token.use_count() == 1);  // the vectors' destructors released the rest
}

}  // namespace

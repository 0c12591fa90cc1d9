#pragma once
// ChunkedVector<T, kChunk>: an indexed sequence that grows in chunks of kChunk. It
// never moves its elements, so growth costs one small allocation per chunk
// instead of a doubling reallocation: in the haptic tick a hierarchy that
// grows its node pool from 2048 to 4096 nodes paid for copying 0.6 MB into
// freshly mapped pages (8 ms on the benchmark machine, where a page fault
// costs several microseconds). Keep a chunk under malloc's mmap threshold
// (128 KB by default), so chunks come from the heap. A chunk is raw storage:
// elements are constructed as they are added, so a query that adds a few
// hundred large elements does not first fill whole chunks with blank ones.

#include <cassert>
#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace argil {

template <class T, std::size_t kChunk>
class ChunkedVector {
  static_assert(kChunk > 0);

 public:
  ChunkedVector() = default;
  ChunkedVector(const ChunkedVector& other) {
    for (std::size_t i = 0; i < other.size_; ++i) push_back(other[i]);
  }
  ChunkedVector(ChunkedVector&& other) noexcept
      : chunks_(std::move(other.chunks_)), size_(std::exchange(other.size_, 0)) {}
  ChunkedVector& operator=(const ChunkedVector& other) {
    if (this != &other) *this = ChunkedVector(other);
    return *this;
  }
  ChunkedVector& operator=(ChunkedVector&& other) noexcept {
    if (this != &other) {
      truncate(0);
      chunks_ = std::move(other.chunks_);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }
  ~ChunkedVector() { truncate(0); }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  T& operator[](std::size_t i) {
    assert(i < size_);
    return *slot(i);
  }
  const T& operator[](std::size_t i) const {
    assert(i < size_);
    return *slot(i);
  }

  /// Appends `value`; references to the other elements stay valid.
  void push_back(T value) {
    if (size_ == chunks_.size() * kChunk)
      chunks_.push_back(std::make_unique_for_overwrite<Storage[]>(kChunk));
    ::new (static_cast<void*>(slot(size_))) T(std::move(value));
    ++size_;
  }

  /// Destroys every element and keeps the chunks for the elements added next
  /// (a scratch store reused from one query to the next touches no fresh memory).
  void clear() {
    for (std::size_t i = 0; i < size_; ++i) slot(i)->~T();
    size_ = 0;
  }

  /// Keeps the first `count` elements (count <= size()): the others are
  /// destroyed and the chunks past the kept ones freed.
  void truncate(std::size_t count) {
    assert(count <= size_);
    for (std::size_t i = count; i < size_; ++i) slot(i)->~T();
    size_ = count;
    chunks_.resize((count + kChunk - 1) / kChunk);
  }

 private:
  // Uninitialised room for one element.
  struct Storage {
    alignas(T) std::byte bytes[sizeof(T)];
  };

  T* slot(std::size_t i) const {
    return std::launder(reinterpret_cast<T*>(chunks_[i / kChunk][i % kChunk].bytes));
  }

  std::vector<std::unique_ptr<Storage[]>> chunks_;
  std::size_t size_ = 0;
};

}  // namespace argil

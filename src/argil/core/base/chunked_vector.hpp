#pragma once
// ChunkedVector<T, kChunk>: an indexed sequence that grows in chunks of kChunk. It
// never moves its elements, so growth costs one small allocation per chunk
// instead of a doubling reallocation: in the haptic tick a hierarchy that
// grows its node pool from 2048 to 4096 nodes paid for copying 0.6 MB into
// freshly mapped pages (8 ms on the benchmark machine, where a page fault
// costs several microseconds). Keep a chunk under malloc's mmap threshold
// (128 KB by default), so chunks come from the heap.

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <memory>
#include <vector>

namespace argil {

template <class T, std::size_t kChunk>
class ChunkedVector {
 public:
  ChunkedVector() = default;
  ChunkedVector(const ChunkedVector& other) : size_(other.size_) {
    for (const std::unique_ptr<T[]>& c : other.chunks_) {
      chunks_.push_back(std::make_unique<T[]>(kChunk));
      std::copy(c.get(), c.get() + kChunk, chunks_.back().get());
    }
  }
  ChunkedVector(ChunkedVector&&) noexcept = default;
  ChunkedVector& operator=(const ChunkedVector& other) {
    if (this != &other) *this = ChunkedVector(other);
    return *this;
  }
  ChunkedVector& operator=(ChunkedVector&&) noexcept = default;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  T& operator[](std::size_t i) {
    assert(i < size_);
    return chunks_[i / kChunk][i % kChunk];
  }
  const T& operator[](std::size_t i) const {
    assert(i < size_);
    return chunks_[i / kChunk][i % kChunk];
  }

  /// Appends `value`; references to the other elements stay valid.
  void push_back(T value) {
    if (size_ == chunks_.size() * kChunk) chunks_.push_back(std::make_unique<T[]>(kChunk));
    chunks_[size_ / kChunk][size_ % kChunk] = std::move(value);
    ++size_;
  }

  /// Keeps the first `count` elements (count <= size()): the chunks past
  /// them are freed, and the kept chunk's later slots reset to T{}.
  void truncate(std::size_t count) {
    assert(count <= size_);
    for (std::size_t i = count; i < size_ && i % kChunk != 0; ++i) (*this)[i] = T{};
    chunks_.resize((count + kChunk - 1) / kChunk);
    size_ = count;
  }

 private:
  std::vector<std::unique_ptr<T[]>> chunks_;
  std::size_t size_ = 0;
};

}  // namespace argil

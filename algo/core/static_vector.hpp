#pragma once
// A vector with its capacity fixed at compile time: no heap, and overflow is counted, not fatal.

#include <array>
#include <cstddef>
#include <cstdint>

namespace irloc {

// Holds up to Capacity elements in place. push_back on a full vector drops the element and
// counts it, so that per-frame code can report "N blobs did not fit" instead of misbehaving.
template <typename T, std::size_t Capacity>
class StaticVector {
 public:
  static constexpr std::size_t capacity() { return Capacity; }

  // Returns false (and counts the drop) when full.
  bool push_back(const T& value) {
    if (size_ == Capacity) {
      ++dropped_;
      return false;
    }
    items_[size_++] = value;
    return true;
  }
  void pop_back() { --size_; }
  // Empties the vector and forgets earlier drops.
  void clear() {
    size_ = 0;
    dropped_ = 0;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == Capacity; }
  // How many push_back calls found the vector full since the last clear().
  std::uint32_t dropped() const { return dropped_; }
  bool overflowed() const { return dropped_ > 0; }

  T& operator[](std::size_t i) { return items_[i]; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  T& back() { return items_[size_ - 1]; }
  const T& back() const { return items_[size_ - 1]; }
  T* begin() { return items_.data(); }
  T* end() { return items_.data() + size_; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + size_; }

 private:
  std::array<T, Capacity> items_{};
  std::size_t size_ = 0;
  std::uint32_t dropped_ = 0;
};

}  // namespace irloc

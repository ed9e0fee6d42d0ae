#pragma once
// Per-frame scratch memory: one buffer allocated at start-up, handed out in aligned pieces
// while a frame is processed and taken back all at once before the next frame.

#include <cstddef>
#include <memory>
#include <span>
#include <type_traits>

namespace irloc {

class ScratchArena {
 public:
  // The only allocation: capacity_bytes of storage, made here, at start-up.
  explicit ScratchArena(std::size_t capacity_bytes);

  // count uninitialized elements of T aligned for T, or an empty span when the arena is out of
  // room (then exhausted() is true until reset()). Never falls back to the heap.
  template <typename T>
  std::span<T> allocate(std::size_t count) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>,
                  "the arena neither constructs nor destroys");
    void* memory = allocate_bytes(count * sizeof(T), alignof(T));
    if (memory == nullptr) return {};
    return {static_cast<T*>(memory), count};
  }

  // Takes back everything handed out; the start of every frame.
  void reset();

  std::size_t capacity() const { return capacity_; }
  std::size_t used() const { return used_; }
  // The most ever in use at once: what to size the arena by.
  std::size_t high_water() const { return high_water_; }
  bool exhausted() const { return exhausted_; }

 private:
  void* allocate_bytes(std::size_t size, std::size_t alignment);

  std::unique_ptr<std::byte[]> storage_;
  std::size_t capacity_ = 0;
  std::size_t used_ = 0;
  std::size_t high_water_ = 0;
  bool exhausted_ = false;
};

}  // namespace irloc

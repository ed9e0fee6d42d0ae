#include "algo/core/scratch_arena.hpp"

#include <algorithm>
#include <cstdint>

namespace irloc {

ScratchArena::ScratchArena(std::size_t capacity_bytes)
    : storage_(std::make_unique<std::byte[]>(capacity_bytes)), capacity_(capacity_bytes) {}

void ScratchArena::reset() {
  used_ = 0;
  exhausted_ = false;
}

void* ScratchArena::allocate_bytes(std::size_t size, std::size_t alignment) {
  const auto base = reinterpret_cast<std::uintptr_t>(storage_.get());
  const std::uintptr_t aligned = (base + used_ + alignment - 1) & ~(std::uintptr_t{alignment} - 1);
  const std::size_t start = aligned - base;
  if (start > capacity_ || size > capacity_ - start) {
    exhausted_ = true;
    return nullptr;
  }
  used_ = start + size;
  high_water_ = std::max(high_water_, used_);
  return storage_.get() + start;
}

}  // namespace irloc

#pragma once
// Counts heap allocations, to prove that per-frame code allocates nothing after start-up.
//
// Every global operator new (plain, array, aligned, nothrow) of a test binary counts, which
// covers new, the standard containers and std::string. While a counter is alive, Eigen's own
// allocations are forbidden too (an assertion in Debug builds: the sanitizer run).

#include <cstdint>

namespace irloc::test {

// Allocations made by this process so far.
std::uint64_t allocations_so_far();

// Counts the allocations made between its construction and count().
//   AllocationCounter counter;
//   pipeline.process(frame);
//   EXPECT_EQ(counter.count(), 0u);
class AllocationCounter {
 public:
  AllocationCounter();
  ~AllocationCounter();
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  std::uint64_t count() const { return allocations_so_far() - start_; }

 private:
  std::uint64_t start_;
  bool eigen_was_allowed_;
};

}  // namespace irloc::test

// irlocd-soak: every operator new is counted by the tests' allocation counter
// (firmware/allocation_count.hpp).

#include "firmware/allocation_count.hpp"

// tests/support/allocation_counter.cpp, linked into irlocd-soak alone; declared here so that
// firmware/ includes nothing from tests/.
namespace irloc::test {
std::uint64_t allocations_so_far();
}

namespace irloc::firmware {

std::uint64_t (*allocation_count())() { return &irloc::test::allocations_so_far; }

}  // namespace irloc::firmware

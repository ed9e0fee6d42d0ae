#pragma once
// Which allocation counter the irlocd binary carries, chosen at link time: irlocd links
// allocations_uncounted.cpp (none), irlocd-soak links allocations_counted.cpp (the tests'
// counter of every operator new), so that one compiled irlocd_main serves both.

#include <cstdint>

namespace irloc::firmware {

// The process's count of allocations so far, or nullptr where this binary does not count them.
std::uint64_t (*allocation_count())();

}  // namespace irloc::firmware

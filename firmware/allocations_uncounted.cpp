// irlocd: allocations are not counted (firmware/allocation_count.hpp).

#include "firmware/allocation_count.hpp"

namespace irloc::firmware {

std::uint64_t (*allocation_count())() { return nullptr; }

}  // namespace irloc::firmware

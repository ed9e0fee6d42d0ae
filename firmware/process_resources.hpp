#pragma once
// What this process holds, for the soak's flat-resources check: resident memory and open file
// descriptors, read from /proc/self. Allocates (it lists a folder): call it outside the frame loop.

#include <cstdint>

namespace irloc::firmware {

struct ProcessResources {
  std::uint64_t resident_kib = 0;
  std::uint64_t open_fds = 0;
};

// Zeros where /proc is not mounted.
ProcessResources read_process_resources();

}  // namespace irloc::firmware

#include "firmware/process_resources.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace irloc::firmware {

ProcessResources read_process_resources() {
  ProcessResources resources;
  {
    // /proc/self/statm: size resident shared ... in pages. Closed before the descriptors are counted.
    std::ifstream statm("/proc/self/statm");
    std::uint64_t size_pages = 0, resident_pages = 0;
    if (statm >> size_pages >> resident_pages) {
      resources.resident_kib = resident_pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE)) / 1024;
    }
  }
  std::error_code error;
  std::filesystem::directory_iterator fds("/proc/self/fd", error);
  if (error) return resources;
  for (const auto& entry : fds) {
    (void)entry;
    ++resources.open_fds;
  }
  // The listing's own descriptor is one of them.
  if (resources.open_fds > 0) --resources.open_fds;
  return resources;
}

}  // namespace irloc::firmware

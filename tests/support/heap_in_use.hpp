#pragma once
// Bytes the process's heap holds now (glibc's mallinfo2: small blocks and mmapped ones), for the
// benchmarks that report what a start-up allocates.

#include <malloc.h>

#include <cstddef>

namespace irloc::test {

inline std::size_t heap_in_use() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

}  // namespace irloc::test

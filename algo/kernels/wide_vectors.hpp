#pragma once
// GCC vectors of kBytes bytes for kernels written once and compiled at several widths: 16 bytes
// (SSE2 on x86-64, NEON on aarch64: every lane operation and comparison native) and, on x86-64, 32
// bytes in an AVX2 version and, for some kernels, 64 bytes in an AVX-512 (x86-64-v4) version,
// picked at load time by the CPU (GCC function multiversioning). A comparison of a vector wider
// than the target's registers is lowered lane by lane, hence the separate builds rather than one
// wide source. Loads and stores go through memcpy: any alignment.
//
// A kernel is defined in an anonymous namespace of its .cpp, once per width it is built at,
//   IRLOC_WIDE_KERNEL_16 void name_wide(args) { body<16>(args); }
//   IRLOC_WIDE_KERNEL_32(void name_wide(args) { body<32>(args); })
//   IRLOC_WIDE_KERNEL_64(void name_wide(args) { body<64>(args); })   // where it pays
// and called by the plain function its header declares (through the CPU's pick on x86-64). body
// is an always_inline template, and so is every helper that handles vectors: helpers
// take vectors by const reference and no call passes or returns one, so GCC's note that a 32-byte
// vector's calling convention differs with AVX (-Wpsabi) concerns no code, and is off here.

#include <cstdint>
#include <cstring>
#include <type_traits>

#pragma GCC diagnostic ignored "-Wpsabi"

namespace irloc::wide {

template <typename T, int kBytes>
struct VectorOf {
  typedef T type __attribute__((vector_size(kBytes)));
};
template <typename T, int kBytes>
using Vec = typename VectorOf<T, kBytes>::type;

template <typename T, int kBytes>
inline constexpr int kLanes = kBytes / static_cast<int>(sizeof(T));

template <typename V, typename T>
__attribute__((always_inline)) inline V load(const T* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <typename V, typename T>
__attribute__((always_inline)) inline void store(T* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

// A row's last, partial vector is read as the row's last kLanes pixels, which overlap pixels a full
// vector already covered: this mask keeps the lanes of the rest of the row only (the last `rest`
// lanes all ones, 0 < rest < kLanes), so that they are counted once.
template <typename V>
__attribute__((always_inline)) inline V last_lanes(int rest) {
  using Lane = std::remove_cvref_t<decltype(V{}[0])>;
  static constexpr int kCount = static_cast<int>(sizeof(V) / sizeof(Lane));
  // kCount zero lanes, then kCount lanes of ones: the window starting at rest.
  static constexpr auto kWindow = [] {
    struct {
      Lane lanes[2 * kCount];
    } window{};
    for (int k = kCount; k < 2 * kCount; ++k) window.lanes[k] = static_cast<Lane>(~Lane{0});
    return window;
  }();
  return load<V>(kWindow.lanes + rest);
}

}  // namespace irloc::wide

#if defined(__x86_64__)
#define IRLOC_WIDE_KERNEL_16 __attribute__((target("default")))
#define IRLOC_WIDE_KERNEL_32(...) __attribute__((target("avx2"))) __VA_ARGS__
// Clang builds (make fuzz) have no AVX-512 version: Debian 12's clang 14 cannot version a function
// for an x86-64 level, so there the AVX2 version serves AVX-512 CPUs too.
#if defined(__clang__)
#define IRLOC_WIDE_KERNEL_64(...)
#else
#define IRLOC_WIDE_KERNEL_64(...) __attribute__((target("arch=x86-64-v4"))) __VA_ARGS__
#endif
#else
#define IRLOC_WIDE_KERNEL_16
#define IRLOC_WIDE_KERNEL_32(...)
#define IRLOC_WIDE_KERNEL_64(...)
#endif

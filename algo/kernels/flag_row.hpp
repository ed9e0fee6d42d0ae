#pragma once
// The fused front end's pass over one row of a frame pair. Internal to algo/kernels.

#include <cstdint>
#include <cstring>

#include "algo/kernels/strobe_check.hpp"

namespace irloc::detail {

// flags[i] = max(on[i] - off[i] - threshold, 0) for i < n: nonzero exactly where the strobe
// difference is above the threshold. Returns whether any flag is set; if so, the row's full
// 64-pixel blocks also as bits: bit k of bits[b] set iff flags[64 b + k] != 0, for b < n / 64.
bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t* flags, std::uint64_t* bits);
bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t* flags, std::uint64_t* bits);

// The strobe counts of a frame in progress, kept in the lanes of the widest vector the row pass uses
// (8-bit counters for 8-bit pixels, 16-bit ones for 16-bit pixels) from one row to the next: the
// row pass empties them into strobe before a lane could wrap, and count_rest() at the frame's end.
// Emptying them once per row cost more than a 640-pixel row's counting.
struct StrobeLaneCounts {
  static constexpr int kBytes = 64;
  alignas(kBytes) unsigned char brighter_on[kBytes] = {};
  alignas(kBytes) unsigned char brighter_off[kBytes] = {};
  int vectors = 0;  // added to the lanes since they were last emptied

  // Adds what the lanes hold to strobe and clears them.
  template <typename Pixel>
  void count_rest(StrobeCounts& strobe) {
    strobe.brighter_on += sum<Pixel>(brighter_on);
    strobe.brighter_off += sum<Pixel>(brighter_off);
    *this = StrobeLaneCounts{};
  }

 private:
  template <typename Pixel>
  static std::uint64_t sum(const unsigned char* bytes) {
    std::uint64_t total = 0;
    for (int k = 0; k < kBytes; k += static_cast<int>(sizeof(Pixel))) {
      Pixel lane;
      std::memcpy(&lane, bytes + k, sizeof lane);
      total += lane;
    }
    return total;
  }
};

// The same, and in the same pass adds to lanes the pixels with on - off > noise_level and
// off - on > noise_level (the strobe check's evidence; lanes.count_rest<Pixel>() after the last row).
bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t noise_level, std::uint8_t* flags, std::uint64_t* bits, StrobeLaneCounts& lanes,
                           StrobeCounts& strobe);
bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t noise_level, std::uint16_t* flags, std::uint64_t* bits,
                           StrobeLaneCounts& lanes, StrobeCounts& strobe);

}  // namespace irloc::detail

#include "algo/kernels/fused_front_end.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "algo/kernels/run_scan.hpp"
#include "algo/kernels/flag_row.hpp"

namespace irloc {
namespace {

// area * max intensity * max(width, height)^2 bounds every blob sum (blob.hpp).
bool blob_sums_fit(const FrontEndConfig& config) {
  __extension__ typedef unsigned __int128 Uint128;
  const auto side = static_cast<Uint128>(std::max(config.width, config.height));
  const Uint128 bound = static_cast<Uint128>(config.width) * static_cast<Uint128>(config.height) *
                        ((Uint128{1} << config.value_bits) - 1) * side * side;
  return bound < (Uint128{1} << 64);
}

FrontEndConfig checked(const FrontEndConfig& config) {
  if (config.width <= 0 || config.height <= 0) throw std::invalid_argument("FusedFrontEnd: frame size must be positive");
  if (config.value_bits < 1 || config.value_bits > 16) throw std::invalid_argument("FusedFrontEnd: value_bits must be 1..16");
  if (!blob_sums_fit(config)) throw std::invalid_argument("FusedFrontEnd: frame too large for exact 64-bit blob sums");
  return config;
}

// The pair is read a few rows ahead of the row pass: it mostly comes from beyond the second-level
// cache (a camera frame, or the last pair's rows evicted), and the hardware prefetcher alone left
// the row pass waiting on it (about a tenth of the 640x480 front end's time, docs/kernels.md). Two
// rows: from four on, at 1280x960, the prefetches wait on the misses still in flight, and the
// pass with them.
constexpr int kPrefetchRows = 2;

template <typename Pixel>
void prefetch_rows(const Pixel* on_row, const Pixel* off_row, int width) {
  const auto row_bytes = static_cast<std::size_t>(width) * sizeof(Pixel);
  const auto* on_bytes = reinterpret_cast<const char*>(on_row);
  const auto* off_bytes = reinterpret_cast<const char*>(off_row);
  for (std::size_t offset = 0; offset < row_bytes; offset += 64) {
    __builtin_prefetch(on_bytes + offset);
    __builtin_prefetch(off_bytes + offset);
  }
}

}  // namespace

FusedFrontEnd::FusedFrontEnd(const FrontEndConfig& config)
    : config_(checked(config)),
      runs_(config.max_runs),
      flags_(static_cast<std::size_t>(config.width)),
      flag_bits_(static_cast<std::size_t>(config.width + 63) / 64) {}

BlobCounters FusedFrontEnd::process(ImageView8 on, ImageView8 off, std::uint8_t threshold, BlobList& blobs) {
  return run<std::uint8_t>(on, off, threshold, 0, blobs, nullptr);
}

BlobCounters FusedFrontEnd::process(ImageView16 on, ImageView16 off, std::uint16_t threshold, BlobList& blobs) {
  return run<std::uint16_t>(on, off, threshold, 0, blobs, nullptr);
}

BlobCounters FusedFrontEnd::process(ImageView8 on, ImageView8 off, std::uint8_t threshold, std::uint8_t noise_level,
                                    BlobList& blobs, StrobeCounts& strobe) {
  return run<std::uint8_t>(on, off, threshold, noise_level, blobs, &strobe);
}

BlobCounters FusedFrontEnd::process(ImageView16 on, ImageView16 off, std::uint16_t threshold, std::uint16_t noise_level,
                                    BlobList& blobs, StrobeCounts& strobe) {
  return run<std::uint16_t>(on, off, threshold, noise_level, blobs, &strobe);
}

template <typename Pixel>
BlobCounters FusedFrontEnd::run(ImageView<const Pixel> on, ImageView<const Pixel> off, Pixel threshold,
                                Pixel noise_level, BlobList& blobs, StrobeCounts* strobe) {
  assert(on.same_size(config_.width, config_.height) && off.same_size(config_.width, config_.height));
  const int width = on.width();
  Pixel* flags = flag_row<Pixel>();
  std::uint64_t* bits = flag_bits_.data();
  // A flag is I - threshold.
  const auto intensity = [flags, threshold](int x) { return static_cast<std::uint32_t>(flags[x]) + threshold; };
  runs_.begin_frame();
  BlobCounters counters;
  detail::StrobeLaneCounts strobe_lanes;
  for (int y = 0; y < on.height(); ++y) {
    if (y + kPrefetchRows < on.height()) prefetch_rows(on.row(y + kPrefetchRows), off.row(y + kPrefetchRows), width);
    // One vector pass flags the row (and counts the strobe evidence); a dark row (most rows of a
    // sparse frame) ends there.
    const bool any = strobe != nullptr ? detail::flag_difference_above(on.row(y), off.row(y), width, threshold,
                                                                       noise_level, flags, bits, strobe_lanes, *strobe)
                                       : detail::flag_difference_above(on.row(y), off.row(y), width, threshold, flags,
                                                                       bits);
    if (!any) continue;
    counters.foreground_pixels += detail::scan_runs(bits, flags, width, [&](int begin, int end) {
      runs_.add_run(y, begin, end, run_sums(begin, end, intensity));
    });
  }
  if (strobe != nullptr) strobe_lanes.count_rest<Pixel>(*strobe);
  runs_.collect(BlobParams{config_.min_area}, blobs, counters);
  return counters;
}

}  // namespace irloc

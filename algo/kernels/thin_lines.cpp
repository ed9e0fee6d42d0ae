#include "algo/kernels/thin_lines.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <stdexcept>

#include "algo/kernels/flag_row.hpp"
#include "algo/kernels/run_scan.hpp"

namespace irloc {
namespace {

// out(x) = AND (kErode) or OR (dilate) of in(x + d) over |d| <= r, x < width; pixels outside the
// row are ignored (they read as the operation's neutral value). padded: words + 2 of scratch:
// the row with a word of border each side, where bit P is pixel P - 64. Returns whether any
// output bit is set.
template <bool kErode>
bool filter_row(const std::uint64_t* in, int words, int width, int r, std::uint64_t* padded, std::uint64_t* out) {
  constexpr std::uint64_t kNeutral = kErode ? ~std::uint64_t{0} : 0;
  const int total = words + 2;
  padded[0] = kNeutral;
  std::memcpy(padded + 1, in, static_cast<std::size_t>(words) * sizeof(std::uint64_t));
  if (width % 64 != 0) padded[words] |= kNeutral << (width % 64);
  padded[total - 1] = kNeutral;
  // a(P) = a(P) op a(P + s), 0 < s < 64, in place (word i reads word i + 1 before it changes).
  const auto combine = [&](int s) {
    for (int i = 0; i < total; ++i) {
      const std::uint64_t next = i + 1 < total ? padded[i + 1] : kNeutral;
      const std::uint64_t shifted = (padded[i] >> s) | (next << (64 - s));
      padded[i] = kErode ? padded[i] & shifted : padded[i] | shifted;
    }
  };
  // Doubling: a(P) = op over [P, P + span), span the largest power of two <= 2r + 1; then the
  // window [P, P + 2r + 1) as two overlapping spans.
  const int length = 2 * r + 1;
  int span = 1;
  for (; 2 * span <= length; span *= 2) combine(span);
  if (length > span) combine(length - span);
  // out(x) = a(x - r + 64): bits from offset 64 - r; none past the width.
  for (int w = 0; w < words; ++w) out[w] = r == 0 ? padded[w + 1] : (padded[w] >> (64 - r)) | (padded[w + 1] << r);
  if (width % 64 != 0) out[words - 1] &= (std::uint64_t{1} << (width % 64)) - 1;
  std::uint64_t any = 0;
  for (int w = 0; w < words; ++w) any |= out[w];
  return any != 0;
}

}  // namespace

ThinLineExtractor::ThinLineExtractor(int width, int height, int element_radius)
    : radius_(element_radius),
      binary_(width, height),
      eroded_rows_(width, height),
      eroded_(width, height),
      dilated_columns_(width, height),
      opened_(width, height),
      lines_(width, height) {
  if (element_radius < 0 || element_radius > kMaxRadius) {
    throw std::invalid_argument("ThinLineExtractor: element radius outside [0, 63]");
  }
  flags_.assign(static_cast<std::size_t>(binary_.words_per_row()) * 64, 0);
  padded_.assign(static_cast<std::size_t>(binary_.words_per_row()) + 2, 0);
  set_rows_before_.assign(static_cast<std::size_t>(height) + 1, 0);
}

template <typename Pixel>
void ThinLineExtractor::binarize(ImageView<const Pixel> on, ImageView<const Pixel> off, Pixel threshold) {
  assert(on.same_size(binary_.width(), binary_.height()) && off.same_size(binary_.width(), binary_.height()));
  // The row pass gives the full 64-pixel blocks as bits; a partial last block is packed from the
  // flags, whose lanes past the width stay 0 (never written).
  Pixel* flags = reinterpret_cast<Pixel*>(flags_.data());
  const int full_blocks = binary_.width() / 64;
  for (int y = 0; y < binary_.height(); ++y) {
    std::uint64_t* bits = binary_.row(y);
    if (!detail::flag_difference_above(on.row(y), off.row(y), on.width(), threshold, flags, bits)) {
      binary_.clear_row(y);
      continue;
    }
    if (full_blocks < binary_.words_per_row()) bits[full_blocks] = detail::pack_flag_block(flags + 64 * full_blocks);
    binary_.set_row_flag(y, true);
  }
}

void ThinLineExtractor::binarize(std::span<const PixelRun> runs, int x0, int y0) {
  for (int y = 0; y < binary_.height(); ++y) binary_.clear_row(y);
  const auto first = std::lower_bound(runs.begin(), runs.end(), y0, [](const PixelRun& run, int y) { return run.y < y; });
  for (auto run = first; run != runs.end() && run->y - y0 < binary_.height(); ++run) {
    const int begin = std::max(run->x_begin - x0, 0);
    const int end = std::min(run->x_end - x0, binary_.width());
    if (begin < end) binary_.set_range(run->y - y0, begin, end);
  }
}

void ThinLineExtractor::extract(std::span<const PixelRun> runs, int x0, int y0) {
  binarize(runs, x0, y0);
  open_and_subtract();
}

void ThinLineExtractor::extract(ImageView8 on, ImageView8 off, std::uint8_t threshold) {
  binarize(on, off, threshold);
  open_and_subtract();
}

void ThinLineExtractor::extract(ImageView16 on, ImageView16 off, std::uint16_t threshold) {
  binarize(on, off, threshold);
  open_and_subtract();
}

void ThinLineExtractor::open_and_subtract() {
  erode_rows();
  erode_columns();
  dilate_columns();
  dilate_rows_and_subtract();
}

void ThinLineExtractor::count_set_rows(const BitImage& image) {
  for (int y = 0; y < image.height(); ++y) set_rows_before_[y + 1] = set_rows_before_[y] + (image.row_set(y) ? 1 : 0);
}

int ThinLineExtractor::set_rows_in(int from, int to) const { return set_rows_before_[to] - set_rows_before_[from]; }

void ThinLineExtractor::erode_rows() {
  for (int y = 0; y < binary_.height(); ++y) {
    if (!binary_.row_set(y)) {
      eroded_rows_.clear_row(y);
      continue;
    }
    eroded_rows_.set_row_flag(y, true);  // so that clear_row() below clears what filter_row wrote
    if (!filter_row<true>(binary_.row(y), binary_.words_per_row(), binary_.width(), radius_, padded_.data(),
                          eroded_rows_.row(y))) {
      eroded_rows_.clear_row(y);
    }
  }
}

// Only where every row of the window is set.
void ThinLineExtractor::erode_columns() {
  const int height = binary_.height();
  const int words = binary_.words_per_row();
  count_set_rows(eroded_rows_);
  for (int y = 0; y < height; ++y) {
    const int from = std::max(0, y - radius_), to = std::min(height, y + radius_ + 1);
    if (set_rows_in(from, to) != to - from) {
      eroded_.clear_row(y);
      continue;
    }
    std::uint64_t* out = eroded_.row(y);
    std::uint64_t any = 0;
    for (int w = 0; w < words; ++w) {
      std::uint64_t word = ~std::uint64_t{0};
      for (int k = from; k < to; ++k) word &= eroded_rows_.row(k)[w];
      out[w] = word;
      any |= word;
    }
    eroded_.set_row_flag(y, true);
    if (any == 0) eroded_.clear_row(y);
  }
}

// Only where a row of the window is set.
void ThinLineExtractor::dilate_columns() {
  const int height = binary_.height();
  const int words = binary_.words_per_row();
  count_set_rows(eroded_);
  for (int y = 0; y < height; ++y) {
    const int from = std::max(0, y - radius_), to = std::min(height, y + radius_ + 1);
    if (set_rows_in(from, to) == 0) {
      dilated_columns_.clear_row(y);
      continue;
    }
    std::uint64_t* out = dilated_columns_.row(y);
    std::fill_n(out, words, std::uint64_t{0});
    for (int k = from; k < to; ++k) {
      if (!eroded_.row_set(k)) continue;
      const std::uint64_t* row = eroded_.row(k);
      for (int w = 0; w < words; ++w) out[w] |= row[w];
    }
    dilated_columns_.set_row_flag(y, true);
  }
}

// The last dilation makes the opening; the lines are the mask without it.
void ThinLineExtractor::dilate_rows_and_subtract() {
  const int words = binary_.words_per_row();
  for (int y = 0; y < binary_.height(); ++y) {
    if (!dilated_columns_.row_set(y)) {
      opened_.clear_row(y);
    } else {
      opened_.set_row_flag(y, true);
      filter_row<false>(dilated_columns_.row(y), words, binary_.width(), radius_, padded_.data(), opened_.row(y));
    }
    if (!binary_.row_set(y)) {
      lines_.clear_row(y);
      continue;
    }
    const std::uint64_t* mask = binary_.row(y);
    const std::uint64_t* opened = opened_.row(y);
    std::uint64_t* lines = lines_.row(y);
    std::uint64_t any = 0;
    for (int w = 0; w < words; ++w) {
      lines[w] = mask[w] & ~opened[w];
      any |= lines[w];
    }
    lines_.set_row_flag(y, true);
    if (any == 0) lines_.clear_row(y);
  }
}

}  // namespace irloc

// Strobe difference, fixed threshold and the automatic thresholds against plain references.
#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "algo/kernels/auto_threshold.hpp"
#include "algo/kernels/difference.hpp"
#include "algo/kernels/difference_noise.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "algo/kernels/threshold.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

struct Size {
  int width;
  int height;
  int padding;
};
// 1x1, odd widths around the vector lengths, padded strides.
constexpr std::array<Size, 8> kSizes{{{1, 1, 0}, {1, 7, 3}, {15, 3, 1}, {17, 5, 0}, {31, 4, 9}, {33, 9, 7},
                                      {64, 8, 0}, {101, 37, 11}}};

template <typename Pixel>
void expect_same_pixels(const PaddedImage<Pixel>& a, const PaddedImage<Pixel>& b) {
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) ASSERT_EQ(a.at(x, y), b.at(x, y)) << "at (" << x << ", " << y << ")";
  }
}

template <typename Pixel>
void check_difference(int max_value) {
  std::mt19937 rng(7);
  for (const Size size : kSizes) {
    PaddedImage<Pixel> on(size.width, size.height, size.padding), off(size.width, size.height, size.padding);
    PaddedImage<Pixel> fast(size.width, size.height, size.padding, 0x5a), slow(size.width, size.height, size.padding, 0x5a);
    test::fill_random(on, rng, max_value);
    test::fill_random(off, rng, max_value);
    subtract_saturating(on.view(), off.view(), fast.view());
    reference::subtract_saturating<Pixel>(on.view(), off.view(), slow.view());
    expect_same_pixels(fast, slow);
    EXPECT_EQ(fast.storage(), slow.storage()) << "the padding must stay untouched";
  }
}

TEST(Difference, Matches8BitReferenceOnRandomImages) { check_difference<std::uint8_t>(255); }
TEST(Difference, Matches16BitReferenceOnRandomImages) { check_difference<std::uint16_t>(65535); }

TEST(Difference, SaturatesAtZeroAndKeepsFullScale) {
  PaddedImage<std::uint8_t> on(40, 2), off(40, 2), out(40, 2);
  on.fill(255);
  off.fill(0);
  off.at(3, 1) = 255;
  subtract_saturating(on.view(), off.view(), out.view());
  EXPECT_EQ(out.at(0, 0), 255);
  EXPECT_EQ(out.at(3, 1), 0);
  on.fill(0);
  off.fill(255);
  subtract_saturating(on.view(), off.view(), out.view());
  EXPECT_EQ(out.at(39, 1), 0);
}

TEST(Difference, WorksInPlace) {
  PaddedImage<std::uint16_t> on(19, 3), off(19, 3);
  on.fill(1000);
  off.fill(400);
  subtract_saturating(on.view(), off.view(), on.view());
  EXPECT_EQ(on.at(18, 2), 600);
}

TEST(Threshold, MatchesReferenceAt8And16Bits) {
  std::mt19937 rng(11);
  for (const Size size : kSizes) {
    PaddedImage<std::uint8_t> in8(size.width, size.height, size.padding);
    PaddedImage<std::uint16_t> in16(size.width, size.height, size.padding);
    test::fill_random(in8, rng, 255);
    test::fill_random(in16, rng, 4095);
    for (const int t : {0, 1, 127, 254, 255}) {
      PaddedImage<std::uint8_t> fast(size.width, size.height, size.padding, 7), slow(size.width, size.height, size.padding, 7);
      threshold_binary(in8.view(), static_cast<std::uint8_t>(t), 200, fast.view());
      reference::threshold_binary<std::uint8_t>(in8.view(), static_cast<std::uint8_t>(t), 200, slow.view());
      EXPECT_EQ(fast.storage(), slow.storage());
      threshold_binary(in16.view(), static_cast<std::uint16_t>(t * 16), 255, fast.view());
      reference::threshold_binary<std::uint16_t>(in16.view(), static_cast<std::uint16_t>(t * 16), 255, slow.view());
      EXPECT_EQ(fast.storage(), slow.storage());
    }
  }
}

TEST(Threshold, AllZeroAndAllFull) {
  PaddedImage<std::uint8_t> in(21, 3), out(21, 3);
  threshold_binary(in.view(), 0, 255, out.view());
  EXPECT_EQ(out.at(20, 2), 0);
  in.fill(255);
  threshold_binary(in.view(), 254, 255, out.view());
  EXPECT_EQ(out.at(20, 2), 255);
  threshold_binary(in.view(), 255, 255, out.view());
  EXPECT_EQ(out.at(20, 2), 0);  // nothing is above 255
}

// Brute force: the between-class variance of every split in long double.
int otsu_brute_force(const std::vector<std::uint32_t>& bins) {
  long double n = 0, s = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    n += bins[i];
    s += static_cast<long double>(i) * bins[i];
  }
  long double best = -1;
  int best_t = 0;
  long double w1 = 0, s1 = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    w1 += bins[i];
    s1 += static_cast<long double>(i) * bins[i];
    const long double w2 = n - w1;
    if (w1 == 0 || w2 == 0) continue;
    const long double gap = s1 / w1 - (s - s1) / w2;
    const long double score = w1 * w2 * gap * gap;
    if (score > best * (1 + 1e-15L)) {
      best = score;
      best_t = static_cast<int>(i);
    }
  }
  return best_t;
}

TEST(AutoThreshold, OtsuMatchesBruteForce) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::uint32_t> bins(256, 0);
    std::normal_distribution<double> dark(20, 5), bright(150 + trial, 20);
    for (int i = 0; i < 5000; ++i) ++bins[static_cast<std::size_t>(std::clamp(dark(rng), 0.0, 255.0))];
    for (int i = 0; i < 50 * (trial + 1); ++i) ++bins[static_cast<std::size_t>(std::clamp(bright(rng), 0.0, 255.0))];
    EXPECT_EQ(otsu_threshold(bins), otsu_brute_force(bins)) << "trial " << trial;
  }
}

TEST(AutoThreshold, DegenerateHistograms) {
  std::vector<std::uint32_t> bins(256, 0);
  EXPECT_EQ(otsu_threshold(bins), 0);
  bins[9] = 100;
  EXPECT_EQ(otsu_threshold(bins), 0);  // one value: no split
  bins[200] = 1;
  EXPECT_EQ(otsu_threshold(bins), 9);  // two values: split between them (first of the tie)
}

TEST(AutoThreshold, NoiseFloorIgnoresSparseMarkers) {
  std::vector<std::uint32_t> bins(256, 0);
  for (int v = 0; v <= 6; ++v) bins[static_cast<std::size_t>(v)] = 10000;  // noise 0..6
  bins[180] = 30;                                                         // markers
  const NoiseFloorParams params{999'000, 4};
  EXPECT_EQ(noise_floor_threshold(bins, params), 6 + 4);
  // Noise only: Otsu would split the noise; the automatic threshold stays above it.
  bins[180] = 0;
  EXPECT_GE(automatic_threshold(bins, params), 10);
  bins[180] = 30;
  const int t = automatic_threshold(bins, params);
  EXPECT_GE(t, 10);
  EXPECT_LT(t, 180);
}

TEST(AutoThreshold, DifferenceHistogramOfAStrobePair) {
  PaddedImage<std::uint8_t> on(64, 48, 5), off(64, 48, 5);
  std::mt19937 rng(5);
  test::make_strobe_pair(on, off, rng, 6);
  std::vector<std::uint32_t> bins(256, 0), expected(256, 0);
  const HistogramShape shape{8, 8};
  accumulate_difference_histogram(on.view(), off.view(), 1, shape, bins);
  PaddedImage<std::uint8_t> difference(64, 48);
  reference::subtract_saturating<std::uint8_t>(on.view(), off.view(), difference.view());
  accumulate_histogram(difference.view(), shape, expected);
  EXPECT_EQ(bins, expected);
  // Every other row, coarse bins, 16-bit.
  PaddedImage<std::uint16_t> on16(64, 48), off16(64, 48);
  test::make_strobe_pair(on16, off16, rng, 6, 4095);
  const HistogramShape coarse{12, 6};
  std::vector<std::uint32_t> coarse_bins(64, 0);
  accumulate_difference_histogram(on16.view(), off16.view(), 2, coarse, coarse_bins);
  std::uint64_t total = 0;
  for (const auto c : coarse_bins) total += c;
  EXPECT_EQ(total, 64u * 24u);
  EXPECT_EQ(coarse.threshold_value(0), 63u);
}

// Windows from 0 up to any first bin and the large bins from there together equal the plain
// histogram, added to what the histogram held, and each window adds to its own bins only: 8 and
// 16 bit, widths on and off every vector width, sampled rows, with differences beyond the windows
// (noise and dots, clamped into the last bin) and with none (a uniform difference of 3, over enough
// rows that the lane counters are emptied on the way).
template <typename Pixel>
void expect_windows_and_large_bins_equal_plain(const PaddedImage<Pixel>& on, const PaddedImage<Pixel>& off,
                                               int row_step, HistogramShape shape) {
  std::vector<std::uint32_t> expected(static_cast<std::size_t>(shape.bins()), 7);
  accumulate_difference_histogram(on.view(), off.view(), row_step, shape, expected);
  for (const int windows : {1, 2, shape.bins() / kDifferenceBinWindow}) {
    SCOPED_TRACE(testing::Message() << windows << " windows of " << shape.bins() << " bins");
    std::vector<std::uint32_t> bins(static_cast<std::size_t>(shape.bins()), 7);
    for (int first = 0; first < windows * kDifferenceBinWindow; first += kDifferenceBinWindow) {
      accumulate_difference_bin_window(on.view(), off.view(), row_step, shape, first, bins);
      const auto window_end = bins.begin() + first + kDifferenceBinWindow;
      EXPECT_TRUE(std::equal(bins.begin(), window_end, expected.begin()));
      EXPECT_TRUE(std::all_of(window_end, bins.end(), [](std::uint32_t count) { return count == 7; }));
    }
    if (windows * kDifferenceBinWindow < shape.bins()) {
      accumulate_large_difference_bins(on.view(), off.view(), row_step, shape, windows * kDifferenceBinWindow, bins);
    }
    EXPECT_EQ(bins, expected);
  }
}

TEST(AutoThreshold, DifferenceBinWindowsAndLargeBinsEqualThePlainHistogram) {
  std::mt19937 rng(11);
  for (const int width : {1, 100, 128, 131, 640}) {
    SCOPED_TRACE(testing::Message() << "width " << width);
    PaddedImage<std::uint8_t> on(width, 40, 3), off(width, 40, 3);
    test::make_strobe_pair(on, off, rng, 6);
    expect_windows_and_large_bins_equal_plain(on, off, 3, HistogramShape{8, 8});
    expect_windows_and_large_bins_equal_plain(on, off, 1, HistogramShape{8, 5});
    on.fill(5);
    off.fill(2);
    expect_windows_and_large_bins_equal_plain(on, off, 1, HistogramShape{8, 8});

    PaddedImage<std::uint16_t> on16(width, 40, 2), off16(width, 40, 2);
    test::make_strobe_pair(on16, off16, rng, 6, 4095);
    expect_windows_and_large_bins_equal_plain(on16, off16, 2, HistogramShape{10, 10});
    expect_windows_and_large_bins_equal_plain(on16, off16, 1, HistogramShape{12, 8});
    on16.fill(5);
    off16.fill(2);
    expect_windows_and_large_bins_equal_plain(on16, off16, 1, HistogramShape{10, 10});
  }
}

template <typename Pixel>
void expect_the_whole_histograms_noise(const PaddedImage<Pixel>& on, const PaddedImage<Pixel>& off, int rows) {
  DifferenceNoiseEstimator estimator(on.height(), rows);
  const DifferenceNoise noise = estimator.estimate(on.view(), off.view());
  const DifferenceNoise expected = reference::difference_noise(ImageView<const Pixel>(on.view()),
                                                               ImageView<const Pixel>(off.view()), on.height() / rows);
  EXPECT_EQ(noise.median, expected.median);
  EXPECT_EQ(noise.sigma, expected.sigma);
}

// Whether the lowest window of bins holds both quantiles (sparse 8-bit noise; three quarters of
// the pixels exactly) or a window above it does, or none of the windows counted in vector lanes
// (differences above 128 grey levels), the estimate is the whole histogram's.
TEST(DifferenceNoise, IsTheWholeHistogramsEstimate) {
  std::mt19937 rng(3);
  PaddedImage<std::uint8_t> on(640, 96, 5), off(640, 96, 5);
  test::make_strobe_pair(on, off, rng, 20);
  expect_the_whole_histograms_noise(on, off, 48);
  PaddedImage<std::uint16_t> on16(131, 96, 3), off16(131, 96, 3);
  test::make_strobe_pair(on16, off16, rng, 20, 4095);
  expect_the_whole_histograms_noise(on16, off16, 48);
  // 3 of 4 pixels differ by `low`, the others by low + 2 (the upper quartile's bin): the window
  // ending at `low` holds the quartile; then one pixel less.
  for (const int low : {7, 127}) {
    SCOPED_TRACE(testing::Message() << "low " << low);
    PaddedImage<std::uint8_t> edge_on(64, 4), edge_off(64, 4);
    edge_off.fill(10);
    edge_on.fill(static_cast<std::uint8_t>(10 + low));
    for (int x = 0; x < 64; ++x) edge_on.at(x, 3) = static_cast<std::uint8_t>(12 + low);
    expect_the_whole_histograms_noise(edge_on, edge_off, 4);
    edge_on.at(0, 0) = static_cast<std::uint8_t>(12 + low);
    expect_the_whole_histograms_noise(edge_on, edge_off, 4);
  }
  // 16 bit, differences beyond the last bin (1022 grey levels).
  PaddedImage<std::uint16_t> far_on(70, 8), far_off(70, 8);
  far_off.fill(100);
  far_on.fill(2100);
  for (int x = 0; x < 70; x += 3) far_on.at(x, 5) = 700;
  expect_the_whole_histograms_noise(far_on, far_off, 8);
}

TEST(AutoThreshold, AllocatesNothing) {
  PaddedImage<std::uint8_t> on(64, 48), off(64, 48);
  std::array<std::uint32_t, 256> bins{};
  test::AllocationCounter counter;
  accumulate_difference_histogram(on.view(), off.view(), 1, HistogramShape{}, bins);
  const int t = automatic_threshold(bins, NoiseFloorParams{});
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GE(t, 0);
}

}  // namespace
}  // namespace irloc

// The strobe check fused into the front end: its counts against the scalar check on random and
// strobe-like pairs (8 and 16 bit, odd widths, padded strides, rows longer than a lane counter
// can count), the verdicts, the blobs unchanged by counting, and the shared pair pass (also over
// a sequence of pairs whose thresholds differ).
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "algo/kernels/fused_front_end.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "algo/kernels/strobe_check.hpp"
#include "tests/kernels/expect_same_blob.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

template <typename Pixel>
void expect_counts_match_scalar_check(int width, int height, int max_value, int noise_level, unsigned seed) {
  SCOPED_TRACE(testing::Message() << width << "x" << height << " noise " << noise_level << " max " << max_value);
  std::mt19937 rng(seed);
  PaddedImage<Pixel> on(width, height, 5, 77), off(width, height, 5, 33);
  test::fill_random(on, rng, max_value);
  test::fill_random(off, rng, max_value);
  FusedFrontEnd front_end({.width = width, .height = height, .value_bits = max_value == 255 ? 8 : 16});
  BlobList blobs;
  StrobeCounts counts;
  front_end.process(on.view(), off.view(), static_cast<Pixel>(max_value / 2), static_cast<Pixel>(noise_level), blobs,
                    counts);
  const StrobeCounts expected = reference::strobe_counts(ImageView<const Pixel>(on.view()),
                                                         ImageView<const Pixel>(off.view()), noise_level);
  EXPECT_EQ(counts.brighter_on, expected.brighter_on);
  EXPECT_EQ(counts.brighter_off, expected.brighter_off);
}

TEST(StrobeCounts, EqualTheScalarCheck8Bit) {
  unsigned seed = 1;
  for (const int width : {1, 31, 32, 33, 100, 1456}) {
    for (const int noise_level : {0, 12, 254, 255}) expect_counts_match_scalar_check<std::uint8_t>(width, 7, 255, noise_level, seed++);
  }
}

TEST(StrobeCounts, EqualTheScalarCheck16Bit) {
  unsigned seed = 100;
  for (const int width : {1, 15, 16, 17, 333}) {
    for (const int noise_level : {0, 12, 4000}) expect_counts_match_scalar_check<std::uint16_t>(width, 5, 4095, noise_level, seed++);
    expect_counts_match_scalar_check<std::uint16_t>(width, 3, 65535, 30000, seed++);
  }
}

// 8-bit lane counters hold 255 vectors (8160 pixels): a longer row empties them on the way.
TEST(StrobeCounts, RowsLongerThanALaneCounterCounts) {
  expect_counts_match_scalar_check<std::uint8_t>(8160 * 2 + 37, 2, 255, 12, 7);
  expect_counts_match_scalar_check<std::uint8_t>(8160 * 2 + 37, 2, 255, 0, 8);
}

TEST(StrobeCounts, CountingLeavesTheBlobsAsTheyWere) {
  std::mt19937 rng(3);
  PaddedImage<std::uint8_t> on(203, 151, 3), off(203, 151, 3);
  test::make_strobe_pair(on, off, rng, 12);
  FusedFrontEnd front_end({.width = 203, .height = 151});
  BlobList plain, counted;
  StrobeCounts counts;
  const BlobCounters a = front_end.process(on.view(), off.view(), 25, plain);
  const BlobCounters b = front_end.process(on.view(), off.view(), 25, 12, counted, counts);
  EXPECT_EQ(a.foreground_pixels, b.foreground_pixels);
  EXPECT_EQ(a.components, b.components);
  ASSERT_EQ(plain.size(), counted.size());
  ASSERT_GT(plain.size(), 0u);
  for (std::size_t i = 0; i < plain.size(); ++i) {
    EXPECT_EQ(plain[i].area, counted[i].area);
    EXPECT_EQ(plain[i].sum_ix, counted[i].sum_ix);
    EXPECT_EQ(plain[i].sum_iy, counted[i].sum_iy);
  }
  EXPECT_GT(counts.brighter_on, counts.brighter_off);
}

StrobeVerdict verdict_of(ImageView8 on, ImageView8 off) {
  FusedFrontEnd front_end({.width = on.width(), .height = on.height()});
  BlobList blobs;
  StrobeCounts counts;
  front_end.process(on, off, 25, StrobeCheckSettings{}.noise_level, blobs, counts);
  return strobe_verdict(counts, {});
}

TEST(StrobeCheck, TheCheckRejectsSwappedAndFlatPairs) {
  std::vector<std::uint8_t> dark(16 * 16, 20), lit(16 * 16, 20);
  for (int i = 0; i < 10; ++i) lit[static_cast<std::size_t>(i * 17)] = 200;
  const ImageView8 on(lit.data(), 16, 16, 16);
  const ImageView8 off(dark.data(), 16, 16, 16);
  EXPECT_EQ(verdict_of(on, off), StrobeVerdict::verified);
  EXPECT_EQ(verdict_of(off, on), StrobeVerdict::swapped);
  EXPECT_EQ(verdict_of(off, off), StrobeVerdict::no_contrast);
}

TEST(StrobeCheck, VerdictFollowsTheSettings) {
  const StrobeCheckSettings settings{.noise_level = 12, .min_contrast_ratio = 3, .min_pixels = 4};
  EXPECT_EQ(strobe_verdict({.brighter_on = 3, .brighter_off = 0}, settings), StrobeVerdict::no_contrast);
  EXPECT_EQ(strobe_verdict({.brighter_on = 4, .brighter_off = 0}, settings), StrobeVerdict::verified);
  EXPECT_EQ(strobe_verdict({.brighter_on = 30, .brighter_off = 10}, settings), StrobeVerdict::verified);
  EXPECT_EQ(strobe_verdict({.brighter_on = 29, .brighter_off = 10}, settings), StrobeVerdict::no_contrast);
  EXPECT_EQ(strobe_verdict({.brighter_on = 10, .brighter_off = 30}, settings), StrobeVerdict::swapped);
}

TEST(PairPass, SharesNoiseBlobsAndCountsAndRelabelsABoundedNumberOfTimes) {
  std::mt19937 rng(5);
  PaddedImage<std::uint8_t> on(320, 240), off(320, 240);
  test::make_strobe_pair(on, off, rng, 20);
  PairPassConfig config;
  config.front_end = {.width = 320, .height = 240};
  PairPass pass(config);
  const GrayImageView on_view = ImageView8(on.view());
  const GrayImageView off_view = ImageView8(off.view());
  pass.analyse(on_view, off_view);  // warm-up
  const PairAnalysis* analysis = nullptr;
  {
    test::AllocationCounter counter;
    analysis = &pass.analyse(on_view, off_view);
    EXPECT_TRUE(pass.relabel(analysis->threshold + 10));
    EXPECT_EQ(counter.count(), 0u);
  }
  // The noise of make_strobe_pair: sigma 2 per frame, so about 2.8 in the difference; the LEDs add 3.
  EXPECT_NEAR(analysis->noise.sigma, 2.8, 0.6);
  EXPECT_NEAR(analysis->noise.median, 3, 1);
  const std::uint32_t threshold = analysis->noise.threshold(5, 6);
  EXPECT_EQ(analysis->threshold, threshold + 10);  // after the relabelling
  EXPECT_EQ(analysis->strobe.brighter_on,
            reference::strobe_counts(ImageView<const std::uint8_t>(on.view()), ImageView<const std::uint8_t>(off.view()), 12)
                .brighter_on);
  // The same blobs as the front end at that threshold.
  FusedFrontEnd front_end(config.front_end);
  BlobList blobs;
  front_end.process(on.view(), off.view(), static_cast<std::uint8_t>(threshold + 10), blobs);
  EXPECT_EQ(analysis->blobs.size(), blobs.size());
  EXPECT_GE(blobs.size(), 15u);
  for (std::uint32_t i = 1; i < PairPass::kMaxRelabels; ++i) EXPECT_TRUE(pass.relabel(threshold));
  EXPECT_FALSE(pass.relabel(threshold + 1));
  EXPECT_EQ(analysis->threshold, threshold);
  EXPECT_EQ(analysis->relabels, PairPass::kMaxRelabels);
  pass.analyse(on_view, off_view);
  EXPECT_EQ(analysis->relabels, 0u);
  EXPECT_EQ(analysis->threshold, threshold);
}

// A pair whose difference is dark but for its dots: its threshold is the floor (min_threshold).
void make_quiet_pair(PaddedImage<std::uint8_t>& on, PaddedImage<std::uint8_t>& off, std::mt19937& rng) {
  test::make_strobe_pair(on, off, rng, 20);
  for (int y = 0; y < on.height(); ++y) {
    for (int x = 0; x < on.width(); ++x) {
      const int dot = on.at(x, y) - off.at(x, y);
      off.at(x, y) = 20;
      on.at(x, y) = static_cast<std::uint8_t>(dot > 40 ? 20 + dot : 20);
    }
  }
}

// What a pair pass that saw no pair before makes of on, off.
void expect_first_pass_analysis(const PairAnalysis& analysis, const PairPassConfig& config, const GrayImageView& on,
                                const GrayImageView& off) {
  PairPass fresh(config);
  const PairAnalysis& expected = fresh.analyse(on, off);
  EXPECT_EQ(analysis.threshold, expected.threshold);
  EXPECT_EQ(analysis.noise.median, expected.noise.median);
  EXPECT_EQ(analysis.noise.sigma, expected.noise.sigma);
  EXPECT_EQ(analysis.strobe.brighter_on, expected.strobe.brighter_on);
  EXPECT_EQ(analysis.strobe.brighter_off, expected.strobe.brighter_off);
  EXPECT_EQ(analysis.blob_counters.foreground_pixels, expected.blob_counters.foreground_pixels);
  EXPECT_EQ(analysis.blob_counters.runs, expected.blob_counters.runs);
  ASSERT_EQ(analysis.blobs.size(), expected.blobs.size());
  for (std::size_t i = 0; i < expected.blobs.size(); ++i) test::expect_same_blob(analysis.blobs[i], expected.blobs[i], i);
}

// After a pair at the floor, the next is labelled before its noise is estimated, at the floor, and
// again at its own threshold where that is above it; after a pair above the floor, the noise comes
// first. Either way each pair gets what it would get alone.
TEST(PairPass, EachPairOfASequenceGetsItsOwnThresholdsBlobs) {
  std::mt19937 rng(6);
  PaddedImage<std::uint8_t> quiet_on(200, 120), quiet_off(200, 120), noisy_on(200, 120), noisy_off(200, 120);
  make_quiet_pair(quiet_on, quiet_off, rng);
  test::make_strobe_pair(noisy_on, noisy_off, rng, 20);
  PairPassConfig config;
  config.front_end = {.width = 200, .height = 120};
  PairPass pass(config);
  struct Step {
    bool noisy;
    bool labelled_twice;
  };
  const Step steps[] = {{false, false}, {false, false}, {true, true}, {true, false}, {false, false}, {true, true},
                        {false, false}, {false, false}, {true, true}};
  for (std::size_t k = 0; k < std::size(steps); ++k) {
    SCOPED_TRACE(testing::Message() << "pair " << k);
    const GrayImageView on = ImageView8((steps[k].noisy ? noisy_on : quiet_on).view());
    const GrayImageView off = ImageView8((steps[k].noisy ? noisy_off : quiet_off).view());
    const PairAnalysis& analysis = pass.analyse(on, off);
    EXPECT_EQ(analysis.threshold == config.min_threshold, !steps[k].noisy);
    EXPECT_EQ(analysis.labelled_twice, steps[k].labelled_twice);
    EXPECT_EQ(analysis.relabels, 0u);
    expect_first_pass_analysis(analysis, config, on, off);
  }
  // A fixed threshold is known before the noise: never a second labelling.
  config.fixed_threshold = 9;
  PairPass fixed(config);
  for (const bool noisy : {false, true, false}) {
    const GrayImageView on = ImageView8((noisy ? noisy_on : quiet_on).view());
    const GrayImageView off = ImageView8((noisy ? noisy_off : quiet_off).view());
    EXPECT_FALSE(fixed.analyse(on, off).labelled_twice);
    expect_first_pass_analysis(fixed.analysis(), config, on, off);
  }
}

}  // namespace
}  // namespace irloc

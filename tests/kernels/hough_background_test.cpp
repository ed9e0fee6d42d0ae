// Hough lines (image and plane-point input, NMS, refinement) and the gated background model.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "algo/kernels/background_model.hpp"
#include "algo/kernels/hough_lines.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

// Draws rho = x cos(theta) + y sin(theta) through the image, one pixel per step along the line.
void draw_line(PaddedImage<std::uint8_t>& image, double rho, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  for (double t = -2000; t <= 2000; t += 0.25) {
    const int x = static_cast<int>(std::lround(rho * c - t * s));
    const int y = static_cast<int>(std::lround(rho * s + t * c));
    if (x >= 0 && y >= 0 && x < image.width() && y < image.height()) image.at(x, y) = 255;
  }
}

double angle_gap(double a, double b) {
  const double d = std::fmod(std::abs(a - b), std::numbers::pi);
  return std::min(d, std::numbers::pi - d);
}

TEST(Hough, TrigTableIsQ14OfTheBinAngles) {
  HoughLines hough(HoughConfig::for_image(100, 100));
  for (int k = 0; k < hough.theta_bins(); ++k) {
    const double theta = std::numbers::pi * k / hough.theta_bins();
    EXPECT_NEAR(hough.cos_of(k).to_double(), std::cos(theta), 1.0 / (1 << 15));
    EXPECT_NEAR(hough.sin_of(k).to_double(), std::sin(theta), 1.0 / (1 << 15));
  }
}

TEST(Hough, FindsAndRefinesSyntheticLines) {
  PaddedImage<std::uint8_t> image(320, 240, 5);
  const double lines_in[][2] = {{100.3, 0.35}, {-40.0, 2.2}, {160.0, std::numbers::pi / 2}, {50.0, 0.0}};
  for (const auto& line : lines_in) draw_line(image, line[0], line[1]);
  HoughLines hough(HoughConfig::for_image(320, 240));
  HoughLineList found;
  const HoughCounters counters = hough.detect(image.view(), found);
  EXPECT_GT(counters.points, 600u);
  EXPECT_EQ(counters.points_dropped, 0u);
  ASSERT_GE(found.size(), 4u);
  for (const auto& line : lines_in) {
    bool matched = false;
    for (std::size_t i = 0; i < 4; ++i) {
      const HoughLine& h = found[i];
      // The same line may come back as (rho, theta) or (-rho, theta +- pi).
      const double sign = std::abs(h.theta - line[1]) > std::numbers::pi / 2 ? -1.0 : 1.0;
      if (angle_gap(h.theta, line[1]) > 0.03 || std::abs(sign * h.rho - line[0]) > 1.5) continue;
      matched = true;
      EXPECT_LT(angle_gap(h.refined_theta, line[1]), 0.004);
      const double refined_sign = std::abs(h.refined_theta - line[1]) > std::numbers::pi / 2 ? -1.0 : 1.0;
      EXPECT_NEAR(refined_sign * h.refined_rho, line[0], 0.5);
      EXPECT_GT(h.inliers, 100u);
    }
    EXPECT_TRUE(matched) << "rho " << line[0] << " theta " << line[1];
  }
  for (std::size_t i = 1; i < found.size(); ++i) EXPECT_GE(found[i - 1].votes, found[i].votes);
}

TEST(Hough, VotesCountEveryPointOncePerAngle) {
  HoughLines hough(HoughConfig::for_image(50, 50));
  const std::vector<PlanePoint> points{{256 * 10, 256 * 20}, {256 * 30, 256 * 5}, {0, 0}};
  HoughLineList found;
  hough.detect(points, found);
  for (int k = 0; k < hough.theta_bins(); k += 17) {
    std::uint32_t total = 0;
    for (int r = 0; r < hough.rho_bins(); ++r) total += hough.votes(k, r);
    EXPECT_EQ(total, 3u);
  }
  // theta = 0: rho = x; the point (10, 20) lands in the bin of rho 10.
  EXPECT_EQ(hough.votes(0, hough.rho_bins() / 2 + 10), 1u);
  EXPECT_TRUE(found.empty());  // 3 points are below min_votes
}

// Every vote lands in the bin the header documents (rho rounded half up from the Q1.14 table,
// bins of rho_resolution centred on 0, clamped beyond rho_max), for points all within rho_max and
// for points some of them beyond it; an odd number of thetas and a resolution that is no power of
// two. Without refinement a peak's line is its cell's.
TEST(Hough, EveryVoteLandsInTheDocumentedBin) {
  HoughConfig config;
  config.theta_bins = 181;
  config.rho_resolution = 1280;
  config.rho_max = 256 * 1000;
  config.min_votes = 4;
  config.refine_peaks = false;
  HoughLines hough(config);
  const std::int64_t res = config.rho_resolution;
  const std::int64_t centre = (config.rho_max + res - 1) / res;
  std::mt19937 rng(11);
  for (const double reach : {0.7, 1.5}) {
    SCOPED_TRACE(testing::Message() << "points out to " << reach << " rho_max");
    std::uniform_real_distribution<double> coordinate(-reach * config.rho_max / std::sqrt(2.0),
                                                      reach * config.rho_max / std::sqrt(2.0));
    std::vector<PlanePoint> points(500);
    for (PlanePoint& p : points) {
      p = {static_cast<std::int32_t>(coordinate(rng)), static_cast<std::int32_t>(coordinate(rng))};
    }
    for (int i = 0; i < 60; ++i) points.push_back({256 * 300 + 37 * i, -256 * 200 + 11 * i});  // a short line
    HoughLineList found;
    hough.detect(points, found);
    std::vector<std::uint32_t> expected(static_cast<std::size_t>(hough.theta_bins() * hough.rho_bins()), 0);
    for (int k = 0; k < hough.theta_bins(); ++k) {
      for (const PlanePoint& p : points) {
        const std::int64_t sum = std::int64_t{p.x} * hough.cos_of(k).raw() + std::int64_t{p.y} * hough.sin_of(k).raw();
        const std::int64_t rho = static_cast<std::int64_t>(std::floor((static_cast<double>(sum) + 8192.0) / 16384.0));
        const std::int64_t bin = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor(static_cast<double>(rho + centre * res + res / 2) / static_cast<double>(res))),
            0, hough.rho_bins() - 1);
        ++expected[static_cast<std::size_t>(k * hough.rho_bins() + bin)];
      }
    }
    for (int k = 0; k < hough.theta_bins(); ++k) {
      for (int r = 0; r < hough.rho_bins(); ++r) {
        ASSERT_EQ(hough.votes(k, r), expected[static_cast<std::size_t>(k * hough.rho_bins() + r)]) << k << "," << r;
      }
    }
    ASSERT_FALSE(found.empty());
    for (const HoughLine& line : found) {
      EXPECT_EQ(line.refined_theta, line.theta);
      EXPECT_EQ(line.refined_rho, line.rho);
      EXPECT_EQ(line.inliers, 0u);
    }
  }
}

TEST(Hough, PlanePointsInSubPixelUnitsAndNoAllocation) {
  // Points on the line x cos(1.0) + y sin(1.0) = 3.7 units, at 1/256 resolution, with half a unit
  // of resolution in rho: the peak is found and refined on the sub-unit coordinates.
  HoughConfig config;
  config.theta_bins = 360;
  config.rho_resolution = 128;
  config.rho_max = 256 * 40;
  config.min_votes = 30;
  config.inlier_distance = 128;
  HoughLines hough(config);
  std::vector<PlanePoint> points;
  const double theta = 1.0, rho = 3.7;
  for (int i = -60; i <= 60; ++i) {
    const double t = i * 0.25;
    const double x = rho * std::cos(theta) - t * std::sin(theta);
    const double y = rho * std::sin(theta) + t * std::cos(theta);
    points.push_back({static_cast<std::int32_t>(std::lround(x * 256)), static_cast<std::int32_t>(std::lround(y * 256))});
  }
  HoughLineList found;
  test::AllocationCounter counter;
  hough.detect(points, found);
  EXPECT_EQ(counter.count(), 0u);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].theta, theta, std::numbers::pi / 360);
  EXPECT_NEAR(found[0].rho, rho, 0.5);
  EXPECT_NEAR(found[0].refined_theta, theta, 1e-3);
  EXPECT_NEAR(found[0].refined_rho, rho, 5e-3);
  EXPECT_EQ(found[0].inliers, 121u);
}

// detect() clears and scans only the rho band its points reach: one HoughLines fed a far, then a
// near, then a far set again gives exactly the votes and lines of a fresh one for each.
TEST(Hough, EachDetectIsIndependentOfTheLast) {
  HoughConfig config;
  config.rho_resolution = 256 * 2;
  config.rho_max = 256 * 400;
  config.min_votes = 8;
  config.nms_rho = 2;
  config.nms_theta = 3;
  std::mt19937 rng(7);
  const auto line_points = [&](double theta, double rho, double spread) {
    std::vector<PlanePoint> points;
    std::uniform_real_distribution<double> along(-spread, spread), noise(-0.3, 0.3);
    for (int i = 0; i < 200; ++i) {
      const double t = along(rng), n = rho + noise(rng);
      points.push_back({static_cast<std::int32_t>(std::lround((n * std::cos(theta) - t * std::sin(theta)) * 256)),
                        static_cast<std::int32_t>(std::lround((n * std::sin(theta) + t * std::cos(theta)) * 256))});
    }
    return points;
  };
  std::vector<PlanePoint> far = line_points(0.3, 300, 50);
  const std::vector<PlanePoint> far_too = line_points(2.0, -250, 100);
  far.insert(far.end(), far_too.begin(), far_too.end());
  std::vector<PlanePoint> near = line_points(1.2, 5, 20);
  HoughLines reused(config);
  for (const std::vector<PlanePoint>* points : {&far, &near, &far, &near}) {
    HoughLines fresh(config);
    HoughLineList expected, found;
    const HoughCounters fresh_counters = fresh.detect(*points, expected);
    const HoughCounters counters = reused.detect(*points, found);
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(counters.peaks, fresh_counters.peaks);
    ASSERT_EQ(found.size(), expected.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].theta_bin, expected[i].theta_bin);
      EXPECT_EQ(found[i].rho_bin, expected[i].rho_bin);
      EXPECT_EQ(found[i].votes, expected[i].votes);
    }
    for (int k = 0; k < fresh.theta_bins(); ++k) {
      for (int r = 0; r < fresh.rho_bins(); ++r) ASSERT_EQ(reused.votes(k, r), fresh.votes(k, r)) << k << "," << r;
    }
  }
}

TEST(Hough, ReportsPeaksBeyondTheListAndRejectsBadConfig) {
  PaddedImage<std::uint8_t> image(200, 200);
  for (int k = 0; k < 40; ++k) draw_line(image, 4.0 * k + 2, 0.0);  // 40 vertical lines
  HoughConfig config = HoughConfig::for_image(200, 200);
  config.nms_rho = 1;
  HoughLines hough(config);
  HoughLineList found;
  const HoughCounters counters = hough.detect(image.view(), found);
  EXPECT_EQ(found.size(), kMaxHoughLines);
  EXPECT_GE(counters.peaks, 40u);
  EXPECT_EQ(counters.peaks_dropped, counters.peaks - kMaxHoughLines);
  HoughConfig bad;
  bad.rho_max = 1 << 30;
  EXPECT_THROW(HoughLines{bad}, std::invalid_argument);
}

TEST(Hough, EmptyAndTinyInputsFindNothing) {
  HoughLines hough(HoughConfig::for_image(1, 1));
  PaddedImage<std::uint8_t> pixel(1, 1);
  HoughLineList found;
  HoughCounters counters = hough.detect(pixel.view(), found);
  EXPECT_EQ(counters.points, 0u);
  EXPECT_TRUE(found.empty());
  pixel.at(0, 0) = 255;
  counters = hough.detect(pixel.view(), found);
  EXPECT_EQ(counters.points, 1u);
  EXPECT_TRUE(found.empty());  // one vote per cell, below min_votes
  counters = hough.detect(std::span<const PlanePoint>{}, found);
  EXPECT_EQ(counters.points, 0u);
}

TEST(Background, ConvergesAndIsGatedByForegroundSize) {
  const BackgroundConfig config{.width = 40, .height = 30, .update_shift = 2, .foreground_threshold = 10,
                                .max_foreground_pixels = 50};
  BackgroundModel model(config);
  PaddedImage<std::uint8_t> frame(40, 30, 3), mask(40, 30);
  frame.fill(100);
  model.reset(frame.view());
  EXPECT_EQ(model.raw_at(5, 5), 100u * 256u);
  // Slow lighting drift to 108: never foreground, absorbed by the running average.
  frame.fill(108);
  for (int i = 0; i < 40; ++i) {
    const BackgroundResult result = model.apply(frame.view(), mask.view());
    EXPECT_EQ(result.foreground_pixels, 0u);
    EXPECT_TRUE(result.updated);
  }
  // Within 2^(shift - 9) grey levels: exact here.
  EXPECT_EQ(model.value_at(39, 29), 108u);
  EXPECT_LE(108u * 256u - model.raw_at(0, 0), 2u);
  // A large object (100 px > gate): foreground, and the background is left alone.
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) frame.at(x, y) = 250;
  }
  const std::uint32_t before = model.raw_at(0, 0);
  BackgroundResult result = model.apply(frame.view(), mask.view());
  EXPECT_EQ(result.foreground_pixels, 100u);
  EXPECT_FALSE(result.updated);
  EXPECT_EQ(mask.at(0, 0), 255);
  EXPECT_EQ(mask.at(20, 20), 0);
  EXPECT_EQ(model.raw_at(0, 0), before);
  // A small object passes the gate; with shift 0 the frame replaces the background.
  BackgroundModel replacing({.width = 40, .height = 30, .update_shift = 0, .foreground_threshold = 10,
                             .max_foreground_pixels = 200});
  replacing.reset(frame.view());
  frame.at(30, 20) = 0;
  result = replacing.apply(frame.view(), mask.view());
  EXPECT_EQ(result.foreground_pixels, 1u);
  EXPECT_TRUE(result.updated);
  EXPECT_EQ(replacing.value_at(30, 20), 0u);
}

TEST(Background, SixteenBitFramesRoundSymmetricallyAndAllocateNothing) {
  BackgroundModel model({.width = 16, .height = 4, .update_shift = 3, .foreground_threshold = 100,
                         .max_foreground_pixels = 64});
  PaddedImage<std::uint16_t> frame(16, 4);
  PaddedImage<std::uint8_t> mask(16, 4);
  frame.fill(4000);
  model.reset(frame.view());
  frame.fill(4010);
  test::AllocationCounter counter;
  model.apply(frame.view(), mask.view());
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(model.raw_at(0, 0), 4000u * 256u + 320u);  // 10 * 256 / 8
  frame.fill(4000);
  model.apply(frame.view(), mask.view());
  EXPECT_EQ(model.raw_at(0, 0), 4000u * 256u + 280u);  // -320 / 8 = -40
  EXPECT_THROW(BackgroundModel({.width = 4, .height = 4, .update_shift = 9}), std::invalid_argument);
}

}  // namespace
}  // namespace irloc

// The kernels against OpenCV, the independent oracle: byte-exact for subtract, threshold,
// erode/dilate and connected components; peak-for-peak for Hough lines.
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "algo/kernels/auto_threshold.hpp"
#include "algo/kernels/blob_labeller.hpp"
#include "algo/kernels/difference.hpp"
#include "algo/kernels/fused_front_end.hpp"
#include "algo/kernels/hough_lines.hpp"
#include "algo/kernels/morphology.hpp"
#include "algo/kernels/threshold.hpp"
#include "tests/kernels/kernel_test_images.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

// A cv::Mat over the same pixels (and stride) as a test image.
template <typename Pixel>
cv::Mat as_mat(PaddedImage<Pixel>& image) {
  constexpr int type = sizeof(Pixel) == 1 ? CV_8UC1 : (sizeof(Pixel) == 2 ? CV_16UC1 : CV_32SC1);
  return cv::Mat(image.height(), image.width(), type, image.view().data(),
                 static_cast<std::size_t>(image.stride()) * sizeof(Pixel));
}

template <typename Pixel>
void expect_equal(PaddedImage<Pixel>& ours, const cv::Mat& theirs) {
  ASSERT_EQ(cv::countNonZero(as_mat(ours) != theirs), 0);
}

struct Size {
  int width;
  int height;
  int padding;
};
const Size kSizes[] = {{1, 1, 0}, {7, 3, 1}, {31, 17, 5}, {64, 48, 0}, {333, 121, 3}};

TEST(OpenCvOracle, SubtractIsSaturating8And16Bit) {
  std::mt19937 rng(1);
  for (const Size s : kSizes) {
    PaddedImage<std::uint8_t> on(s.width, s.height, s.padding), off(s.width, s.height, s.padding), out(s.width, s.height, s.padding);
    test::fill_random(on, rng, 255);
    test::fill_random(off, rng, 255);
    subtract_saturating(on.view(), off.view(), out.view());
    cv::Mat expected;
    cv::subtract(as_mat(on), as_mat(off), expected);
    expect_equal(out, expected);
    PaddedImage<std::uint16_t> on16(s.width, s.height, s.padding), off16(s.width, s.height, s.padding),
        out16(s.width, s.height, s.padding);
    test::fill_random(on16, rng, 65535);
    test::fill_random(off16, rng, 65535);
    subtract_saturating(on16.view(), off16.view(), out16.view());
    cv::subtract(as_mat(on16), as_mat(off16), expected);
    expect_equal(out16, expected);
  }
}

TEST(OpenCvOracle, ThresholdBinary8And16Bit) {
  std::mt19937 rng(2);
  for (const Size s : kSizes) {
    PaddedImage<std::uint8_t> in(s.width, s.height, s.padding), out(s.width, s.height, s.padding);
    PaddedImage<std::uint16_t> in16(s.width, s.height, s.padding);
    test::fill_random(in, rng, 255);
    test::fill_random(in16, rng, 65535);
    for (const int t : {0, 1, 100, 254, 255}) {
      threshold_binary(in.view(), static_cast<std::uint8_t>(t), 255, out.view());
      cv::Mat expected;
      cv::threshold(as_mat(in), expected, t, 255, cv::THRESH_BINARY);
      expect_equal(out, expected);
      threshold_binary(in16.view(), static_cast<std::uint16_t>(t * 257), 255, out.view());
      cv::threshold(as_mat(in16), expected, t * 257, 255, cv::THRESH_BINARY);
      expected.convertTo(expected, CV_8U);
      expect_equal(out, expected);
    }
  }
}

TEST(OpenCvOracle, OtsuThresholdOnStrobeDifferences) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    PaddedImage<std::uint8_t> on(160, 120), off(160, 120), difference(160, 120);
    test::make_strobe_pair(on, off, rng, 5 + trial * 3);
    subtract_saturating(on.view(), off.view(), difference.view());
    std::vector<std::uint32_t> bins(256, 0);
    accumulate_difference_histogram(on.view(), off.view(), 1, HistogramShape{}, bins);
    cv::Mat unused;
    const double expected = cv::threshold(as_mat(difference), unused, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    EXPECT_EQ(otsu_threshold(bins), static_cast<int>(expected)) << "trial " << trial;
  }
}

TEST(OpenCvOracle, ErodeDilateSquareAndCross) {
  std::mt19937 rng(4);
  Morphology morphology(400);
  for (const Size s : kSizes) {
    for (const bool grey : {false, true}) {
      PaddedImage<std::uint8_t> in(s.width, s.height, s.padding), out(s.width, s.height, s.padding);
      if (grey) test::fill_random(in, rng, 255);
      else test::fill_random_mask(in, rng, 75);
      for (const ElementShape shape : {ElementShape::square, ElementShape::cross}) {
        for (const int r : {1, 2, 4}) {
          const cv::Mat element = cv::getStructuringElement(
              shape == ElementShape::square ? cv::MORPH_RECT : cv::MORPH_CROSS, cv::Size(2 * r + 1, 2 * r + 1));
          cv::Mat expected;
          morphology.erode(in.view(), {shape, r}, out.view());
          cv::erode(as_mat(in), expected, element);
          expect_equal(out, expected);
          morphology.dilate(in.view(), {shape, r}, out.view());
          cv::dilate(as_mat(in), expected, element);
          expect_equal(out, expected);
        }
      }
    }
  }
}

// Our labels and OpenCV's must be the same partition: a bijection between label values.
void expect_same_partition(PaddedImage<std::int32_t>& ours, const cv::Mat& theirs) {
  std::map<int, int> forward, backward;
  for (int y = 0; y < ours.height(); ++y) {
    for (int x = 0; x < ours.width(); ++x) {
      const int a = ours.at(x, y);
      const int b = theirs.at<int>(y, x);
      ASSERT_EQ(a == 0, b == 0) << "at " << x << "," << y;
      if (a == 0) continue;
      const auto [it, inserted] = forward.emplace(a, b);
      ASSERT_EQ(it->second, b) << "our label " << a << " splits";
      const auto [jt, inserted_back] = backward.emplace(b, a);
      ASSERT_EQ(jt->second, a) << "OpenCV label " << b << " splits";
    }
  }
}

void check_components(PaddedImage<std::uint8_t>& on, PaddedImage<std::uint8_t>& off, std::uint8_t threshold) {
  const int w = on.width(), h = on.height();
  FusedFrontEnd front_end({.width = w, .height = h});
  BlobList blobs;
  const BlobCounters counters = front_end.process(on.view(), off.view(), threshold, blobs);
  ASSERT_EQ(counters.blobs_dropped, 0u) << "keep the test under kMaxBlobs";
  PaddedImage<std::int32_t> labels(w, h);
  front_end.paint_labels(labels.view());

  cv::Mat difference, mask, cv_labels, stats, centroids;
  cv::subtract(as_mat(on), as_mat(off), difference);
  cv::threshold(difference, mask, threshold, 255, cv::THRESH_BINARY);
  const int count = cv::connectedComponentsWithStats(mask, cv_labels, stats, centroids, 8, CV_32S);
  ASSERT_EQ(static_cast<std::size_t>(count - 1), blobs.size());
  expect_same_partition(labels, cv_labels);
  // Per blob: area, box, geometric centroid; and the intensity centroid against sums in double.
  std::vector<double> si(blobs.size() + 1), sx(blobs.size() + 1), sy(blobs.size() + 1);
  std::vector<int> ours_of(static_cast<std::size_t>(count), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int b = cv_labels.at<int>(y, x);
      if (b == 0) continue;
      ours_of[static_cast<std::size_t>(b)] = labels.at(x, y);
      const double value = difference.at<std::uint8_t>(y, x);
      si[static_cast<std::size_t>(b)] += value;
      sx[static_cast<std::size_t>(b)] += value * x;
      sy[static_cast<std::size_t>(b)] += value * y;
    }
  }
  for (int b = 1; b < count; ++b) {
    const Blob& blob = blobs[static_cast<std::size_t>(ours_of[static_cast<std::size_t>(b)] - 1)];
    EXPECT_EQ(static_cast<int>(blob.area), stats.at<int>(b, cv::CC_STAT_AREA));
    EXPECT_EQ(blob.x_min, stats.at<int>(b, cv::CC_STAT_LEFT));
    EXPECT_EQ(blob.y_min, stats.at<int>(b, cv::CC_STAT_TOP));
    EXPECT_EQ(blob.width(), stats.at<int>(b, cv::CC_STAT_WIDTH));
    EXPECT_EQ(blob.height(), stats.at<int>(b, cv::CC_STAT_HEIGHT));
    EXPECT_NEAR(blob.geometric_centroid_x(), centroids.at<double>(b, 0), 1e-9);
    EXPECT_NEAR(blob.geometric_centroid_y(), centroids.at<double>(b, 1), 1e-9);
    const auto i = static_cast<std::size_t>(b);
    EXPECT_NEAR(blob.centroid_x(), sx[i] / si[i], 1e-3);
    EXPECT_NEAR(blob.centroid_y(), sy[i] / si[i], 1e-3);
    EXPECT_NEAR(blob.centroid_x_q8().to_double(), sx[i] / si[i], 1.0 / 512 + 1e-9);
  }
}

TEST(OpenCvOracle, ConnectedComponentsOnStrobePairs) {
  std::mt19937 rng(5);
  for (const Size s : kSizes) {
    PaddedImage<std::uint8_t> on(s.width, s.height, s.padding), off(s.width, s.height, s.padding);
    test::make_strobe_pair(on, off, rng, s.width / 10 + 1);
    check_components(on, off, 25);
  }
}

TEST(OpenCvOracle, ConnectedComponentsOnRandomMasks) {
  std::mt19937 rng(6);
  for (const int percent : {10, 30, 50, 70, 95}) {
    PaddedImage<std::uint8_t> on(41, 31, 3), off(41, 31, 1);
    test::fill_random_mask(on, rng, percent);
    for (int y = 0; y < on.height(); ++y) {
      for (int x = 0; x < on.width(); ++x) on.at(x, y) = on.at(x, y) ? static_cast<std::uint8_t>(50 + (x * 7 + y) % 200) : 0;
    }
    SCOPED_TRACE(testing::Message() << percent << "%");
    check_components(on, off, 0);
  }
}

TEST(OpenCvOracle, ConnectedComponentsBorderBlobAndFullFrame) {
  PaddedImage<std::uint8_t> on(41, 29, 2), off(41, 29);
  for (int x = 0; x < 41; ++x) on.at(x, 0) = on.at(x, 28) = 90;
  for (int y = 0; y < 29; ++y) on.at(0, y) = on.at(40, y) = 90;
  on.at(20, 14) = 90;
  check_components(on, off, 10);
  on.fill(255);
  check_components(on, off, 0);
}

TEST(OpenCvOracle, HoughLinePeaks) {
  PaddedImage<std::uint8_t> image(320, 240);
  const double truth[][2] = {{100.3, 0.35}, {-40.0, 2.2}, {160.0, std::numbers::pi / 2}, {50.0, 0.0}, {200.0, 1.0}};
  for (const auto& line : truth) {
    const double c = std::cos(line[1]), s = std::sin(line[1]);
    for (double t = -600; t <= 600; t += 0.25) {
      const int x = static_cast<int>(std::lround(line[0] * c - t * s));
      const int y = static_cast<int>(std::lround(line[0] * s + t * c));
      if (x >= 0 && y >= 0 && x < 320 && y < 240) image.at(x, y) = 255;
    }
  }
  HoughConfig config = HoughConfig::for_image(320, 240);
  config.min_votes = 60;
  HoughLines hough(config);
  HoughLineList ours;
  hough.detect(image.view(), ours);
  std::vector<cv::Vec3f> theirs;
  cv::HoughLines(as_mat(image), theirs, 1, CV_PI / 180, 60);
  ASSERT_GE(ours.size(), 5u);
  ASSERT_GE(theirs.size(), 5u);
  // Each of the five strongest peaks on either side has a counterpart on the other within one
  // bin of rho and theta and with about the same votes (the trig tables differ in the last bit).
  const auto close = [](double rho_a, double theta_a, double rho_b, double theta_b) {
    return std::abs(rho_a - rho_b) <= 1.0 + 1e-6 && std::abs(theta_a - theta_b) <= std::numbers::pi / 180 + 1e-6;
  };
  for (std::size_t i = 0; i < 5; ++i) {
    // OpenCV's 4-neighbour suppression also reports weaker cells beside a peak: compare with the
    // strongest of its lines near ours.
    double votes = 0;
    for (const cv::Vec3f& line : theirs) {
      if (close(ours[i].rho, ours[i].theta, line[0], line[1])) votes = std::max<double>(votes, line[2]);
    }
    EXPECT_NEAR(static_cast<double>(ours[i].votes), votes, 0.05 * votes)
        << "our peak " << i << " rho " << ours[i].rho << " theta " << ours[i].theta;
    bool found_back = false;
    for (const HoughLine& line : ours) {
      found_back = found_back || close(line.rho, line.theta, theirs[i][0], theirs[i][1]);
    }
    EXPECT_TRUE(found_back) << "OpenCV peak " << i << " rho " << theirs[i][0] << " theta " << theirs[i][1];
  }
}

}  // namespace
}  // namespace irloc

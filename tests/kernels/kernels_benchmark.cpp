// The dot path's front end on sparse IR strobe pairs, side by side in one run: the fused path,
// the separate kernels, the OpenCV chain and a memcpy of the frame pair; at the Pi 5 camera's
// 1456x1088 also the fused path counting the strobe check's evidence, the Localizer's whole shared
// pass, and the separate scalar strobe check it replaced. Every case times one frame pair; names
// read kind/size (e.g. fused/1280x1024). `make bench` writes build/bench/kernels.json.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "algo/kernels/blob_labeller.hpp"
#include "algo/kernels/difference.hpp"
#include "algo/kernels/fused_front_end.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/kernels/strobe_check.hpp"
#include "algo/kernels/threshold.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/kernels/reference_kernels.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

constexpr int kDots = 40;
constexpr std::uint8_t kThreshold = 25;
constexpr std::uint16_t kThreshold12 = kThreshold << 4;

template <typename Pixel>
struct FramePair {
  FramePair(int width, int height, int max_value) : on(width, height), off(width, height) {
    std::mt19937 rng(42);
    test::make_strobe_pair(on, off, rng, kDots, max_value);
  }
  PaddedImage<Pixel> on;
  PaddedImage<Pixel> off;
};

// Frames are built once per size and shared by every case.
template <typename Pixel>
FramePair<Pixel>& frames(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<FramePair<Pixel>>> cache;
  auto& slot = cache[{width, height}];
  if (!slot) slot = std::make_unique<FramePair<Pixel>>(width, height, sizeof(Pixel) == 1 ? 255 : 4095);
  return *slot;
}

template <typename Pixel>
cv::Mat as_mat(PaddedImage<Pixel>& image) {
  return cv::Mat(image.height(), image.width(), sizeof(Pixel) == 1 ? CV_8UC1 : CV_16UC1, image.view().data(),
                 static_cast<std::size_t>(image.stride()) * sizeof(Pixel));
}

template <typename Pixel>
void set_pair_bytes(benchmark::State& state, int width, int height) {
  state.SetBytesProcessed(state.iterations() * 2 * static_cast<std::int64_t>(width) * height *
                          static_cast<std::int64_t>(sizeof(Pixel)));
}

template <typename Pixel>
void memcpy_pair(benchmark::State& state, int width, int height) {
  auto& pair = frames<Pixel>(width, height);
  PaddedImage<Pixel> on_copy(width, height), off_copy(width, height);
  const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * sizeof(Pixel);
  for (auto _ : state) {
    std::memcpy(on_copy.view().data(), pair.on.view().data(), bytes);
    std::memcpy(off_copy.view().data(), pair.off.view().data(), bytes);
    benchmark::DoNotOptimize(on_copy.view().data());
    benchmark::DoNotOptimize(off_copy.view().data());
    benchmark::ClobberMemory();
  }
  set_pair_bytes<Pixel>(state, width, height);
}

template <typename Pixel>
void fused(benchmark::State& state, int width, int height) {
  auto& pair = frames<Pixel>(width, height);
  FusedFrontEnd front_end({.width = width, .height = height, .value_bits = sizeof(Pixel) == 1 ? 8 : 12});
  BlobList blobs;
  const auto threshold = static_cast<Pixel>(sizeof(Pixel) == 1 ? kThreshold : kThreshold12);
  BlobCounters counters;
  for (auto _ : state) {
    counters = front_end.process(pair.on.view(), pair.off.view(), threshold, blobs);
    benchmark::DoNotOptimize(blobs.begin());
  }
  state.counters["blobs"] = static_cast<double>(blobs.size());
  state.counters["foreground_px"] = counters.foreground_pixels;
  set_pair_bytes<Pixel>(state, width, height);
}

// The fused pass that also counts the strobe check's evidence (what the Localizer runs).
template <typename Pixel>
void fused_strobe(benchmark::State& state, int width, int height) {
  auto& pair = frames<Pixel>(width, height);
  FusedFrontEnd front_end({.width = width, .height = height, .value_bits = sizeof(Pixel) == 1 ? 8 : 12});
  BlobList blobs;
  const auto threshold = static_cast<Pixel>(sizeof(Pixel) == 1 ? kThreshold : kThreshold12);
  const auto noise_level = static_cast<Pixel>(StrobeCheckSettings{}.noise_level << (sizeof(Pixel) == 1 ? 0 : 4));
  StrobeCounts strobe;
  for (auto _ : state) {
    strobe = StrobeCounts{};
    front_end.process(pair.on.view(), pair.off.view(), threshold, noise_level, blobs, strobe);
    benchmark::DoNotOptimize(blobs.begin());
    benchmark::DoNotOptimize(strobe);
  }
  state.counters["blobs"] = static_cast<double>(blobs.size());
  state.counters["brighter_on_px"] = static_cast<double>(strobe.brighter_on);
  set_pair_bytes<Pixel>(state, width, height);
}

// The Localizer's whole shared pass: noise estimate (48 sampled rows), then the fused pass with
// the strobe counts at the threshold derived from it.
void pair_pass(benchmark::State& state, int width, int height) {
  auto& pair = frames<std::uint8_t>(width, height);
  PairPassConfig config;
  config.front_end = {.width = width, .height = height};
  PairPass pass(config);
  const GrayImageView on = ImageView8(pair.on.view());
  const GrayImageView off = ImageView8(pair.off.view());
  for (auto _ : state) benchmark::DoNotOptimize(pass.analyse(on, off).blobs.begin());
  state.counters["blobs"] = static_cast<double>(pass.analysis().blobs.size());
  state.counters["threshold"] = pass.analysis().threshold;
  set_pair_bytes<std::uint8_t>(state, width, height);
}

// Before: irlocd's separate scalar strobe check, a second read of every pixel of the pair.
void strobe_check_scalar(benchmark::State& state, int width, int height) {
  auto& pair = frames<std::uint8_t>(width, height);
  StrobeCounts strobe;
  for (auto _ : state) {
    strobe = reference::strobe_counts(ImageView<const std::uint8_t>(pair.on.view()),
                                      ImageView<const std::uint8_t>(pair.off.view()), StrobeCheckSettings{}.noise_level);
    benchmark::DoNotOptimize(strobe_verdict(strobe, {}));
  }
  state.counters["brighter_on_px"] = static_cast<double>(strobe.brighter_on);
  set_pair_bytes<std::uint8_t>(state, width, height);
}

void separate(benchmark::State& state, int width, int height) {
  auto& pair = frames<std::uint8_t>(width, height);
  PaddedImage<std::uint8_t> difference(width, height), mask(width, height);
  BlobLabeller labeller(std::size_t{1} << 16);
  BlobList blobs;
  for (auto _ : state) {
    subtract_saturating(pair.on.view(), pair.off.view(), difference.view());
    threshold_binary(difference.view(), kThreshold, 255, mask.view());
    labeller.label(mask.view(), difference.view(), {}, blobs);
    benchmark::DoNotOptimize(blobs.begin());
  }
  state.counters["blobs"] = static_cast<double>(blobs.size());
  set_pair_bytes<std::uint8_t>(state, width, height);
}

void opencv_chain(benchmark::State& state, int width, int height, int threads) {
  auto& pair = frames<std::uint8_t>(width, height);
  const int previous_threads = cv::getNumThreads();
  if (threads > 0) cv::setNumThreads(threads);
  const cv::Mat on = as_mat(pair.on), off = as_mat(pair.off);
  cv::Mat difference, mask, labels, stats, centroids;
  int count = 0;
  for (auto _ : state) {
    cv::subtract(on, off, difference);
    cv::threshold(difference, mask, kThreshold, 255, cv::THRESH_BINARY);
    count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
    benchmark::DoNotOptimize(stats.data);
  }
  cv::setNumThreads(previous_threads);
  state.counters["blobs"] = count - 1;
  set_pair_bytes<std::uint8_t>(state, width, height);
}

// The machine running `make bench` may be shared: five repetitions each, reported as mean,
// median and spread, so that one disturbed run does not decide a ratio.
template <typename... Args>
void add(const std::string& name, Args&&... args) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<Args>(args)...)->Repetitions(5)->ReportAggregatesOnly(true);
}

void register_all() {
  for (const auto& [width, height] : {std::pair{640, 480}, std::pair{1280, 1024}}) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    add("memcpy/" + size, memcpy_pair<std::uint8_t>, width, height);
    add("fused/" + size, fused<std::uint8_t>, width, height);
    add("separate/" + size, separate, width, height);
    add("opencv/" + size, opencv_chain, width, height, 0);  // OpenCV's default thread count
    add("opencv_1thread/" + size, opencv_chain, width, height, 1);
    add("memcpy16bit/" + size, memcpy_pair<std::uint16_t>, width, height);
    add("fused16bit/" + size, fused<std::uint16_t>, width, height);
  }
  // The strobe check fused into the front end, at the Pi 5 camera's size (rpi5-gs-mono).
  const int width = 1456;
  const int height = 1088;
  const std::string size = "1456x1088";
  add("memcpy/" + size, memcpy_pair<std::uint8_t>, width, height);
  add("fused/" + size, fused<std::uint8_t>, width, height);
  add("fused_strobe/" + size, fused_strobe<std::uint8_t>, width, height);
  add("pair_pass/" + size, pair_pass, width, height);
  add("strobe_check_scalar/" + size, strobe_check_scalar, width, height);
  add("fused16bit/" + size, fused<std::uint16_t>, width, height);
  add("fused_strobe16bit/" + size, fused_strobe<std::uint16_t>, width, height);
}

}  // namespace
}  // namespace irloc

int main(int argc, char** argv) {
  irloc::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

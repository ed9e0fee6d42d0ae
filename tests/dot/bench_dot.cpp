// The whole dot pipeline per strobe pair at 1280 x 960 (difference, blobs, candidates, grouping,
// decoding, P3P + refinement, confidence: Localizer::process), against AprilTag 3 finding and
// posing one tag36h11 tag in a frame of the same size (Debian's libapriltag, default detector
// settings, one thread). Counters: the mean time of each dot stage (ms) and whether every
// iteration found the marker / tag.

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>

// libapriltag's common/ headers lack C++ guards.
extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>
#include <apriltag/tag36h11.h>
}
#include <benchmark/benchmark.h>

#include "algo/pipeline/localizer.hpp"
#include "tests/dot/dot_scene.hpp"
#include "tests/support/heap_in_use.hpp"

namespace irloc {
namespace {

constexpr int kWidth = 1280;
constexpr int kHeight = 960;
constexpr double kFocal = 1000;  // the field of view of the 640 x 480, f = 500 px test camera

test::Scene dot_scene(bool clutter) {
  test::Scene scene;
  scene.camera = test::pinhole_camera(kWidth, kHeight, kFocal);
  scene.world_from_base = test::level_pose(0.03, -0.02, 0.5);
  scene.add_marker(test::ceiling_marker(1782, 0.0, 0.0, 0.2));
  if (clutter) {
    scene.add_marker(test::ceiling_marker(33, 0.6, 0.3, 1.2));
    scene.add_marker(test::ceiling_marker(2900, -0.5, 0.35, -2.5));
    scene.discs.push_back({{0.3, -0.45, 2.6}, 0.15, 60, 220});   // a lamp
    scene.discs.push_back({{-0.4, -0.3, 2.6}, 0.25, 40, 200});   // another
    scene.discs.push_back({{-0.3, -0.1, 2.6}, 0.012, 140, 0});   // stray reflectors
    scene.discs.push_back({{0.5, -0.2, 2.6}, 0.01, 120, 0});
  }
  return scene;
}

// The scene's three markers, and with `every_id` the other 4,093 IDs too, 0.5 m apart on a
// 32 m x 32 m ceiling beyond the scene (a map using every ID: start-up and per-frame cost).
LocalizerSetup dot_setup(const test::Scene& scene, bool every_id) {
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.map.dot_markers = {test::ceiling_marker(1782, 0.0, 0.0, 0.2), test::ceiling_marker(33, 0.6, 0.3, 1.2),
                           test::ceiling_marker(2900, -0.5, 0.35, -2.5)};
  if (every_id) {
    int cell = 0;
    for (int id = 0; id < 4096; ++id) {
      if (id == 1782 || id == 33 || id == 2900) continue;
      setup.map.dot_markers.push_back(test::ceiling_marker(id, 10 + 0.5 * (cell % 64), 0.5 * (cell / 64), 0.1 * (id % 60)));
      ++cell;
    }
  }
  return setup;
}

void dot_pipeline(benchmark::State& state, bool clutter, std::uint32_t fixed_threshold = 0, bool every_id = false) {
  const test::Scene scene = dot_scene(clutter);
  Image8 on, off;
  scene.render(on, off);
  LocalizerSetup setup = dot_setup(scene, every_id);
  setup.dot.threshold = fixed_threshold;
  Localizer localizer(setup);
  const StrobePair pair = test::strobe_pair(on, off);
  std::map<std::string, double> stage_sums;
  std::int64_t found = 0;
  for (auto _ : state) {
    const PoseEstimate estimate = localizer.process(pair);
    benchmark::DoNotOptimize(estimate);
    found += estimate.ok && estimate.marker_id == 1782 ? 1 : 0;
    for (const StageTime& stage : localizer.last_stage_times()) stage_sums[stage.name] += stage.milliseconds;
  }
  const auto n = static_cast<double>(state.iterations());
  for (const auto& [name, sum] : stage_sums) state.counters[std::string("ms_") + name] = sum / n;
  state.counters["found_fraction"] = static_cast<double>(found) / n;
  if (found != state.iterations()) state.SkipWithError("the dot pipeline missed the marker");
}

void BM_DotPipeline_1280x960_OneMarker(benchmark::State& state) { dot_pipeline(state, false); }
void BM_DotPipeline_1280x960_ThreeMarkersLampsStrays(benchmark::State& state) { dot_pipeline(state, true); }
// The same without the per-frame noise estimate: what the threshold histogram costs.
void BM_DotPipeline_1280x960_OneMarkerFixedThreshold(benchmark::State& state) { dot_pipeline(state, false, 24); }

void BM_DotPipeline_1280x960_ThreeMarkersLampsStrays_MapOf4096(benchmark::State& state) {
  dot_pipeline(state, true, 0, true);
}

// Start-up (Localizer construction) with a map of every ID, and the heap it holds.
void BM_DotStartup_1280x960_MapOf4096(benchmark::State& state) {
  const LocalizerSetup setup = dot_setup(dot_scene(true), true);
  std::size_t heap = 0;
  for (auto _ : state) {
    const std::size_t before = test::heap_in_use();
    Localizer localizer(setup);
    heap = test::heap_in_use() - before;
    benchmark::DoNotOptimize(localizer);
  }
  state.counters["markers"] = static_cast<double>(setup.map.dot_markers.size());
  state.counters["heap_MB"] = static_cast<double>(heap) / 1e6;
}

// One tag36h11 tag, 9 px per module (a 90 px tag, about the image size of a 16 cm tag at 2.3 m),
// on a mid-grey ceiling with the same Gaussian noise as the dot frames.
void BM_AprilTag3_1280x960_DetectAndPoseOneTag36h11(benchmark::State& state) {
  apriltag_family_t* family = tag36h11_create();
  apriltag_detector_t* detector = apriltag_detector_create();
  apriltag_detector_add_family(detector, family);
  detector->nthreads = 1;

  image_u8_t* tag = apriltag_to_image(family, 7);
  image_u8_t* frame = image_u8_create(kWidth, kHeight);
  constexpr int kModule = 9;
  const int x0 = kWidth / 2 - tag->width * kModule / 2, y0 = kHeight / 2 - tag->height * kModule / 2;
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      double value = 120;
      const int tx = (x - x0) / kModule, ty = (y - y0) / kModule;
      if (x >= x0 && y >= y0 && tx < tag->width && ty < tag->height) value = tag->buf[ty * tag->stride + tx] ? 230 : 20;
      frame->buf[y * frame->stride + x] = static_cast<std::uint8_t>(std::clamp(std::lround(value + noise(random)), 0L, 255L));
    }
  }
  std::int64_t found = 0;
  for (auto _ : state) {
    zarray_t* detections = apriltag_detector_detect(detector, frame);
    for (int i = 0; i < zarray_size(detections); ++i) {
      apriltag_detection_t* detection = nullptr;
      zarray_get(detections, i, &detection);
      apriltag_detection_info_t info{detection, 0.16, kFocal, kFocal, (kWidth - 1) / 2.0, (kHeight - 1) / 2.0};
      apriltag_pose_t pose;
      benchmark::DoNotOptimize(estimate_tag_pose(&info, &pose));
      // Debian's libapriltag does not export matd_destroy; a matd_t is one calloc'd block.
      std::free(pose.R);
      std::free(pose.t);
      found += detection->id == 7 ? 1 : 0;
    }
    apriltag_detections_destroy(detections);
  }
  state.counters["found_fraction"] = static_cast<double>(found) / static_cast<double>(state.iterations());
  if (found != state.iterations()) state.SkipWithError("AprilTag missed the tag");
  image_u8_destroy(frame);
  image_u8_destroy(tag);
  apriltag_detector_destroy(detector);
  tag36h11_destroy(family);
}

BENCHMARK(BM_DotPipeline_1280x960_OneMarker)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DotPipeline_1280x960_ThreeMarkersLampsStrays)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DotPipeline_1280x960_OneMarkerFixedThreshold)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DotPipeline_1280x960_ThreeMarkersLampsStrays_MapOf4096)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DotStartup_1280x960_MapOf4096)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AprilTag3_1280x960_DetectAndPoseOneTag36h11)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc

BENCHMARK_MAIN();

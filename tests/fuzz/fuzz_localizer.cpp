// libFuzzer target: the per-frame pipeline of every pose source on arbitrary frame pairs. The
// first byte chooses the source (dot, square, LED landmarks, outside-in), the robot's dof and the
// pixel depth; the other bytes fill the frames. process() must never throw, crash or hang.
// Each configuration's Localizer is made on its first input and restarted (Localizer::restart)
// for every later one: its start-up tables were most of an input's cost. The frames are 80 x 60:
// every stage and bound of the pipeline is reached as at full size, and arbitrary bytes make
// nearly every pixel foreground, so an input's cost is its pixel count. The per-frame budgets are
// small for the same reason: on frames of noise every budget is spent, so its size sets an input's
// cost, while a small one reaches the same branches, its own limit included: the LED search's 20
// solver calls finish the 6 triples (dof 6) or 18 ordered pairs (dof 3, 4) of 3 detections and
// give up on the 24 or 36 of its 4; two box fits per frame, fewer than a noise frame's blobs; the
// square's ceiling out to 46 degrees, about a quarter of the Hough accumulator at 75.
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include "algo/core/image.hpp"
#include "algo/pipeline/localizer.hpp"
#include "tests/fuzz/fuzz_files.hpp"
#include "tests/outside_in/outside_in_drive.hpp"

namespace {

using namespace irloc;

LocalizerSetup ceiling_setup(int kind, Dof dof, bool wide) {
  LocalizerSetup setup;
  setup.camera = CameraIntrinsics{80, 60, 21, 21, 39.5, 29.5, LensModel::equisolid, {}};
  setup.mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  setup.mount.translation = Eigen::Vector3d(0.05, 0, 0.3);
  setup.dof = dof;
  setup.dot.pixel_bits = wide ? 12 : 8;
  if (kind == 0) {
    // Made in place: copying a DotMarker with its empty optional sigma trips GCC 12's
    // maybe-uninitialized at -O2.
    DotMarker& marker = setup.map.dot_markers.emplace_back();
    marker.id = 1782;
    marker.origin = Eigen::Vector3d(0.2, 0.1, 2.6);
    marker.yaw = 0.3;
  }
  if (kind == 1) {
    SquareMarker square;
    square.name = "hall";
    square.corners = {Eigen::Vector3d(-1, -1, 2.3), Eigen::Vector3d(1, -1, 2.3), Eigen::Vector3d(1, 1, 2.3),
                      Eigen::Vector3d(-1, 1, 2.3)};
    setup.map.square_markers.push_back(square);
    setup.square.max_ray_angle = 0.8;
  }
  if (kind == 2) {
    setup.map.led_landmarks.push_back({"L1", Eigen::Vector3d(1, 0.5, 2.5), std::nullopt, std::nullopt});
    setup.map.led_landmarks.push_back({"L2", Eigen::Vector3d(-1, 0.8, 2.5), std::nullopt, std::nullopt});
    setup.map.led_landmarks.push_back({"L3", Eigen::Vector3d(0.3, -1.2, 2.4), std::nullopt, std::nullopt});
    setup.led.search_detections = 4;
    setup.led.max_hypotheses = 20;
  }
  return setup;
}

// Pixel i is the input's byte (i x stride + offset) mod size (two bytes for 16-bit pixels), the
// index stepped without a division per pixel. The target's own loop, not code under test: it runs
// without AddressSanitizer's check per pixel (its index stays below size by construction).
template <typename Pixel>
__attribute__((no_sanitize("address"))) void fill(std::vector<Pixel>& pixels, const std::uint8_t* data, std::size_t size, std::size_t stride, std::size_t offset) {
  if (size == 0) return;
  const std::size_t step = stride % size;
  std::size_t at = offset % size;
  Pixel* const end = pixels.data() + pixels.size();
  for (Pixel* pixel = pixels.data(); pixel != end; ++pixel) {
    if constexpr (sizeof(Pixel) == 1) {
      *pixel = data[at];
    } else {
      *pixel = static_cast<Pixel>(data[at] * 17 + data[at + 1 < size ? at + 1 : 0]);
    }
    at += step;
    if (at >= size) at -= size;
  }
}

// The process's frame buffers, sized on first use.
template <typename Pixel>
std::vector<Pixel>& frame_buffer(int which, std::size_t pixels) {
  static std::vector<Pixel> buffers[2];
  buffers[which].resize(pixels);
  return buffers[which];
}

template <typename Pixel, typename View>
void run_pairs(Localizer& localizer, const std::uint8_t* data, std::size_t size, int width, int height, bool paired) {
  std::vector<Pixel>& on = frame_buffer<Pixel>(0, static_cast<std::size_t>(width) * height);
  std::vector<Pixel>& off = frame_buffer<Pixel>(1, on.size());
  for (int pair = 0; pair < 3; ++pair) {
    fill(on, data, size, 1, static_cast<std::size_t>(pair) * 131);
    fill(off, data, size, 7, 3 + static_cast<std::size_t>(pair) * 17);
    StrobePair strobe_pair;
    strobe_pair.on = Frame{2u * pair + 1, std::int64_t(pair) * 100'000'000 + 50'000'000, true, View(on.data(), width, height)};
    if (paired) strobe_pair.off = Frame{2u * pair, std::int64_t(pair) * 100'000'000, false, View(off.data(), width, height)};
    localizer.process(strobe_pair);
  }
}

// The tests' wall camera at an eighth of the resolution.
test::WallCamera eighth_wall_camera() {
  test::WallCamera camera;
  camera.intrinsics = CameraIntrinsics{80, 60, 62.5, 62.5, 39.5, 29.5, LensModel::plumb_bob, {}};
  return camera;
}

LocalizerSetup outside_in_setup() {
  const test::WallCamera camera = eighth_wall_camera();
  LocalizerSetup setup;
  setup.camera = camera.intrinsics;
  setup.outside_in.emplace();
  setup.outside_in->floor_reference = test::floor_reference_of(camera);
  setup.outside_in->max_fits_per_frame = 2;
  return setup;
}

// The Localizer of a configuration (kind, dof, depth), restarted; nullptr where the sources refuse
// the set-up at start-up (reported there, with the file's name).
Localizer* restarted_localizer(int kind, Dof dof, bool wide) {
  static std::map<int, std::unique_ptr<Localizer>> made;
  const int key = kind * 16 + static_cast<int>(dof) * 2 + (wide ? 1 : 0);
  const auto [entry, first] = made.try_emplace(key);
  if (!first) {
    if (entry->second) entry->second->restart();
    return entry->second.get();
  }
  try {
    entry->second = std::make_unique<Localizer>(kind == 3 ? outside_in_setup() : ceiling_setup(kind, dof, wide));
  } catch (const std::invalid_argument&) {
  }
  return entry->second.get();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int kind = data[0] & 3;
  const Dof dof = (data[0] >> 2 & 3) == 0 ? Dof::planar3 : (data[0] >> 2 & 3) == 1 ? Dof::height4 : Dof::full6;
  const bool wide = kind != 3 && (data[0] >> 4 & 1) != 0;
  ++data;
  --size;
  Localizer* localizer = restarted_localizer(kind, kind == 3 ? Dof::planar3 : dof, wide);
  if (localizer == nullptr) return 0;
  const int width = localizer->setup().camera.width, height = localizer->setup().camera.height;
  if (wide) {
    run_pairs<std::uint16_t, ImageView16>(*localizer, data, size, width, height, true);
  } else {
    run_pairs<std::uint8_t, ImageView8>(*localizer, data, size, width, height, kind != 3);
  }
  return 0;
}

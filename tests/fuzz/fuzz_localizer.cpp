// libFuzzer target: the per-frame pipeline of every pose source on arbitrary frame pairs. The
// first byte chooses the source (dot, square, LED landmarks, outside-in), the robot's dof and the
// pixel depth; the other bytes fill the frames. process() must never throw, crash or hang.
#include <cstdint>
#include <optional>
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
  setup.camera = CameraIntrinsics{160, 120, 42, 42, 79.5, 59.5, LensModel::equisolid, {}};
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
  }
  if (kind == 2) {
    setup.map.led_landmarks.push_back({"L1", Eigen::Vector3d(1, 0.5, 2.5), std::nullopt, std::nullopt});
    setup.map.led_landmarks.push_back({"L2", Eigen::Vector3d(-1, 0.8, 2.5), std::nullopt, std::nullopt});
    setup.map.led_landmarks.push_back({"L3", Eigen::Vector3d(0.3, -1.2, 2.4), std::nullopt, std::nullopt});
  }
  return setup;
}

template <typename Pixel>
void fill(std::vector<Pixel>& pixels, const std::uint8_t* data, std::size_t size, std::size_t stride, std::size_t offset) {
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (size == 0) break;
    const std::size_t at = (i * stride + offset) % size;
    pixels[i] = static_cast<Pixel>(sizeof(Pixel) == 1 ? data[at] : data[at] * 17 + data[(at + 1) % size]);
  }
}

template <typename Pixel, typename View>
void run_pairs(Localizer& localizer, const std::uint8_t* data, std::size_t size, int width, int height, bool paired) {
  std::vector<Pixel> on(static_cast<std::size_t>(width) * height), off(on.size());
  for (int pair = 0; pair < 3; ++pair) {
    fill(on, data, size, 1, static_cast<std::size_t>(pair) * 131);
    fill(off, data, size, 7, 3 + static_cast<std::size_t>(pair) * 17);
    StrobePair strobe_pair;
    strobe_pair.on = Frame{2u * pair + 1, std::int64_t(pair) * 100'000'000 + 50'000'000, true, View(on.data(), width, height)};
    if (paired) strobe_pair.off = Frame{2u * pair, std::int64_t(pair) * 100'000'000, false, View(off.data(), width, height)};
    localizer.process(strobe_pair);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int kind = data[0] & 3;
  const Dof dof = (data[0] >> 2 & 3) == 0 ? Dof::planar3 : (data[0] >> 2 & 3) == 1 ? Dof::height4 : Dof::full6;
  const bool wide = (data[0] >> 4 & 1) != 0;
  ++data;
  --size;
  if (kind == 3) {
    test::WallCamera camera;  // the tests' wall camera at a quarter of the resolution
    camera.intrinsics = CameraIntrinsics{160, 120, 125, 125, 79.5, 59.5, LensModel::plumb_bob, {}};
    LocalizerSetup setup;
    setup.camera = camera.intrinsics;
    setup.outside_in.emplace();
    setup.outside_in->floor_reference = test::floor_reference_of(camera);
    Localizer localizer(setup);
    run_pairs<std::uint8_t, ImageView8>(localizer, data, size, camera.intrinsics.width, camera.intrinsics.height, false);
    return 0;
  }
  std::optional<Localizer> localizer;
  try {
    localizer.emplace(ceiling_setup(kind, dof, wide));
  } catch (const std::invalid_argument&) {
    return 0;  // a set-up the sources refuse at start-up (reported there, with the file's name)
  }
  if (wide) {
    run_pairs<std::uint16_t, ImageView16>(*localizer, data, size, 160, 120, true);
  } else {
    run_pairs<std::uint8_t, ImageView8>(*localizer, data, size, 160, 120, true);
  }
  return 0;
}

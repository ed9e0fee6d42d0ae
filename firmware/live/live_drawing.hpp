#pragma once
// The live view's picture of one pose attempt, and the same picture for any dataset offline
// (irlocd --annotate): the LED-on frame or the pair's difference, scaled, with what each source
// found drawn on it and a banner with the attempt's result.
//
//   grey boxes      blobs of the pair's shared pass (on - off above its threshold)
//   green circles   dots of dot markers, labelled with the marker ID
//   red crosses     the same dots reprojected from the attempt's pose
//   yellow          a square's measured corners (0..3) and the sides between them
//   cyan circles    LEDs, labelled with the landmark they were associated with
//   magenta         the map's landmarks reprojected from the pose (dot marker outlines with
//                   their IDs, square sides, LEDs)
//   orange          outside-in: the robot's box at the fitted pose
//
// Drawing allocates (cairo); it runs on the live view's server thread or in an offline run,
// never in the frame loop's per-frame path.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/outside_in/box_silhouette.hpp"
#include "firmware/live/live_snapshot.hpp"

namespace irloc::firmware {

enum class LiveImage { on, difference };

std::optional<LiveImage> live_image_named(std::string_view name);  // "on" or "difference"

// What the drawing needs to reproject landmarks, taken once from the localizer's setup.
struct LiveViewGeometry {
  CameraModel camera;
  RigidTransform camera_from_base;                  // T_C_B of a camera on the robot
  std::optional<RigidTransform> camera_from_world;  // T_C_W of a fixed (outside-in) camera
  std::optional<outside_in::BoxBody> body;          // outside-in: the robot's box
  MarkerMap map;
};

LiveViewGeometry live_view_geometry(const Localizer& localizer);

// A picture in cairo's RGB24 layout: 4 bytes a pixel, B G R X in memory (little-endian hosts).
struct BgrxImage {
  int width = 0, height = 0, stride = 0;  // stride in bytes
  std::vector<std::uint8_t> pixels;
};

// Draws `snapshot` at most `max_width` pixels wide (never enlarged), banner included, into `out`.
// Precondition: snapshot.publication > 0.
void draw_live_view(const LiveSnapshot& snapshot, const LiveViewGeometry& geometry, LiveImage image, int max_width,
                    BgrxImage& out);

}  // namespace irloc::firmware

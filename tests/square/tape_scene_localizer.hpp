#pragma once
// A Localizer for a TapeScene's camera, mount and square (dof 3), and the strobe pair it takes
// from the scene's rendered frames: shared by the square suites that run the whole pipeline.

#include "algo/frames/strobe_pairer.hpp"
#include "algo/pipeline/localizer_setup.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {

inline LocalizerSetup setup_for(const TapeScene& scene) {
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.dof = Dof::planar3;
  setup.map.square_markers.push_back(scene.marker);
  return setup;
}

// The LED-on frame (seq 11) at t_ns 1000, its LED-off partner before it.
inline StrobePair pair_of(const Image8& on, const Image8& off) {
  StrobePair pair;
  pair.on = Frame{.seq = 11, .t_ns = 1000, .led_on = true, .image = ImageView8(on.view())};
  pair.off = Frame{.seq = 10, .t_ns = 900, .led_on = false, .image = ImageView8(off.view())};
  return pair;
}

}  // namespace irloc::test
